// What a run costs the crane (include/crane_twin/analysis/usage_counter.hpp, docs/fatigue.md
// "Usage"): lifts from the lift-off monitor, k_Q, and each hot spot's damage from its stress
// history streamed row by row, against the same history counted whole.
#include "crane_twin/analysis/usage_counter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "crane_twin/analysis/crane_classification.hpp"
#include "crane_twin/analysis/rainflow.hpp"
#include "crane_twin/analysis/usage_store.hpp"
#include "crane_twin/io/input_error.hpp"
#include "crane_twin/io/scene.hpp"

namespace crane_twin {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A synthetic history of 3.6 t on the T8036, rows k0 .. k1 of it at 100 Hz: landed until t = 2,
// lifted (the tension at its static value) with the hoist reeling in at 0.05 m/s, set down from
// 40 to 50 s with the hoist paying out, lifted again until the end at t = 100 s; the hot spots'
// stresses ring with slowly growing amplitudes. `clock` [s] is taken from each row's time (a
// node that started again counts from its own zero).
void feed(const CraneModel& m, UsageCounter& usage, LiftOffMonitor& lift_off, int k0, int k1,
          double clock, std::vector<std::vector<double>>* history = nullptr) {
  const double T = staticTopTension(m, 60.0);
  const int spots = m.hot_spots ? static_cast<int>(m.hot_spots->rows.size()) : 0;
  for (int k = k0; k <= k1; ++k) {
    SeriesValues row;
    const double t = 0.01 * k;
    row.t = t - clock;
    row.payload_landed = t < 2.0 || (t >= 40.0 && t < 50.0);
    row.rope_length = 60.0 - 0.05 * (t < 40.0 ? t : t < 50.0 ? 80.0 - t : t - 20.0);
    row.rope_top_tension = row.payload_landed ? 0.1 * T : T;
    for (int i = 0; i < spots; ++i) {
      const double s = 1e6 * (i + 1) * (1.0 + 0.01 * t) * std::sin(2.0 * kPi * 0.3 * t);
      row.stresses.push_back(s);
      if (history) (*history)[i].push_back(s);
    }
    lift_off.observe(row, T);
    usage.observe(row, lift_off);
  }
}

CraneModel liftOffModel(std::vector<std::string> sets = {}) {
  sets.push_back("rope.elements=10");
  return buildCraneModel(loadScene(
      std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/t8036_lift_off_slow.yaml", sets));
}

TEST(UsageCounter, LiftsKqAndTheDamageOfTheWholeHistory) {
  // The history above: two lifts, four hot spots on category 71 (max_load 12.5 t).
  const CraneModel m = liftOffModel();
  ASSERT_TRUE(m.hot_spots);
  const int spots = static_cast<int>(m.hot_spots->rows.size());
  UsageCounter usage(m);
  LiftOffMonitor lift_off;
  std::vector<std::vector<double>> history(spots);
  feed(m, usage, lift_off, 0, 10000, 0.0, &history);
  const UsageReport r = usage.report();
  EXPECT_NEAR(r.hours, 100.0 / 3600.0, 1e-12);
  ASSERT_EQ(r.lifts.size(), 2u);
  EXPECT_EQ(r.lift_count, 2);
  EXPECT_NEAR(r.lifts[0].lift_off, 2.0, 0.011);
  EXPECT_NEAR(r.lifts[0].set_down, 40.0, 0.011);
  EXPECT_NEAR(r.lifts[1].lift_off, 50.0, 0.011);
  EXPECT_TRUE(std::isnan(r.lifts[1].set_down));
  EXPECT_EQ(r.lifts[0].mass, 3600.0);
  const double kq = std::pow(3600.0 / m.scene.crane->max_load, 3);
  EXPECT_NEAR(r.k_q, kq, 1e-12 * kq);
  ASSERT_EQ(static_cast<int>(r.hot_spots.size()), spots);
  for (int i = 0; i < spots; ++i) {
    const double whole = minerDamage(rainflowCount(history[i]), SnCurve{71.0, 1.0});
    EXPECT_GT(whole, 0.0);
    EXPECT_NEAR(r.hot_spots[i].damage, whole, 1e-12 * whole) << i;
    EXPECT_NEAR(r.hot_spots[i].damage_per_hour, whole / r.hours, 1e-9 * whole / r.hours);
    EXPECT_NEAR(r.hot_spots[i].hours_to_failure, r.hours / whole, 1e-9 * r.hours / whole);
  }
  // Twice the stress, 2^3 the damage (slope 3).
  EXPECT_NEAR(r.hot_spots[1].damage / r.hot_spots[0].damage, 8.0, 1e-9);
}

TEST(UsageCounter, TheStepsBetweenTheRowsCountTheCrestsTheRowsMiss) {
  // Rows every 10 steps of a 7.3 Hz ringing sampled at 1 kHz: the rows alone fall beside the
  // crests; the steps fed between them (each row repeating its last step) count the whole
  // history, as rainflowCount of every step does.
  const CraneModel m = liftOffModel();
  ASSERT_TRUE(m.hot_spots);
  const int spots = static_cast<int>(m.hot_spots->rows.size());
  UsageCounter rows_only(m), with_steps(m);
  LiftOffMonitor lift_off;
  std::vector<std::vector<double>> every_step(spots);
  const auto stresses = [&](int k) {
    Eigen::VectorXd s(spots);
    for (int i = 0; i < spots; ++i)
      s(i) = 1e6 * (i + 1) * std::sin(2.0 * kPi * 7.3 * 0.001 * k + 0.4);
    return s;
  };
  for (int k = 0; k <= 20000; ++k) {
    const Eigen::VectorXd s = stresses(k);
    for (int i = 0; i < spots; ++i) every_step[i].push_back(s(i));
    if (k > 0) with_steps.observeStep(s);
    if (k % 10 != 0) continue;
    SeriesValues row;
    row.t = 0.001 * k;
    row.rope_length = 60.0;
    row.stresses.assign(s.data(), s.data() + spots);
    lift_off.observe(row, 1.0);
    rows_only.observe(row, lift_off);
    with_steps.observe(row, lift_off);
  }
  const UsageReport a = rows_only.report(), b = with_steps.report();
  for (int i = 0; i < spots; ++i) {
    const double whole = minerDamage(rainflowCount(every_step[i]), SnCurve{71.0, 1.0});
    EXPECT_NEAR(b.hot_spots[i].damage, whole, 1e-12 * whole) << i;
    EXPECT_LT(a.hot_spots[i].damage, 0.99 * whole) << i;  // the rows' lower crests
  }
  EXPECT_THROW(with_steps.observeStep(Eigen::VectorXd::Constant(spots, NAN)),
               std::invalid_argument);
}

TEST(UsageCounter, ARunWithoutLiftsOrHotSpotsReportsNothingToCount) {
  const CraneModel m = buildCraneModel(
      loadScene(std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/t8036_live.yaml",
                {"rope.elements=10", "structure.model=rigid"}));
  UsageCounter usage(m);
  LiftOffMonitor lift_off;
  SeriesValues row;
  for (int k = 0; k < 10; ++k) {
    row.t = k;
    lift_off.observe(row, 1.0);
    usage.observe(row, lift_off);
  }
  const UsageReport r = usage.report();
  EXPECT_TRUE(r.lifts.empty());
  EXPECT_EQ(r.k_q, 0.0);
  EXPECT_TRUE(r.hot_spots.empty());
}

TEST(UsageCounter, ClassesAndTheDesignLifeProjection) {
  const CraneModel m = liftOffModel();
  ASSERT_GT(m.scene.crane->design_hours, 0.0);
  UsageCounter usage(m);
  LiftOffMonitor lift_off;
  feed(m, usage, lift_off, 0, 10000, 0.0);
  const UsageReport r = usage.report();
  ASSERT_EQ(r.lift_count, 2);
  EXPECT_EQ(r.u_class, "U0");
  EXPECT_EQ(r.q_class, "Q0");  // (3.6 / 12.5)^3 = 0.0239 <= 0.0313
  EXPECT_EQ(r.design_hours, m.scene.crane->design_hours);
  // Two lifts in 100 s: 72 an hour; 20000 h of that is 1.44e6 lifts, class U7 (1e6 .. 2e6).
  const double projected = 2.0 / r.hours * r.design_hours;
  EXPECT_NEAR(r.lifts_in_design_life, projected, 1e-9 * projected);
  EXPECT_EQ(r.u_class_in_design_life, utilisationClass(projected));
  for (const HotSpotUsage& h : r.hot_spots) {
    EXPECT_EQ(h.short_of_design_life, h.hours_to_failure < r.design_hours) << h.name;
  }
  // A design life between the lives of hot spots 1 and 2 (twice the stress: an eighth of the
  // life): hot spot 1 outlives it, 2 .. 4 fall short.
  CraneModel m2 = m;
  m2.scene.crane->design_hours =
      std::sqrt(r.hot_spots[0].hours_to_failure * r.hot_spots[1].hours_to_failure);
  UsageCounter usage2(m2);
  LiftOffMonitor lift_off2;
  feed(m2, usage2, lift_off2, 0, 10000, 0.0);
  const UsageReport r2 = usage2.report();
  EXPECT_FALSE(r2.hot_spots[0].short_of_design_life);
  for (int i = 1; i < 4; ++i) EXPECT_TRUE(r2.hot_spots[i].short_of_design_life) << i;
  // No design hours, no projection.
  m2.scene.crane->design_hours = 0.0;
  UsageCounter usage3(m2);
  LiftOffMonitor lift_off3;
  feed(m2, usage3, lift_off3, 0, 10000, 0.0);
  EXPECT_EQ(usage3.report().lifts_in_design_life, 0.0);
  EXPECT_EQ(usage3.report().u_class_in_design_life, "");
  for (const HotSpotUsage& h : usage3.report().hot_spots) EXPECT_FALSE(h.short_of_design_life);
}

TEST(UsageCounter, ACountGoesOnFromItsSavedStateAsIfNeverStopped) {
  // One count over the whole history against a count saved at t = 30 s (a lift under way),
  // read back from its file and continued by a new counter and monitor (a node restarted).
  const CraneModel m = liftOffModel();
  const int spots = static_cast<int>(m.hot_spots->rows.size());
  UsageCounter whole(m);
  LiftOffMonitor whole_monitor;
  std::vector<std::vector<double>> history(spots);
  feed(m, whole, whole_monitor, 0, 10000, 0.0, &history);

  UsageCounter first(m);
  LiftOffMonitor first_monitor;
  feed(m, first, first_monitor, 0, 3000, 0.0);
  const std::string file = ::testing::TempDir() + "usage_counter_test.yaml";
  saveUsageState(first.state(), file);
  UsageCounter second(m, loadUsageState(file));
  LiftOffMonitor second_monitor;
  feed(m, second, second_monitor, 3001, 10000, 30.01);

  const UsageReport a = whole.report(), b = second.report();
  EXPECT_NEAR(b.hours, (30.0 + (100.0 - 30.01)) / 3600.0, 1e-12);  // the stop is not counted
  EXPECT_EQ(b.lift_count, 2);
  ASSERT_EQ(b.lifts.size(), 2u);
  EXPECT_NEAR(b.lifts[0].lift_off, a.lifts[0].lift_off, 1e-12);
  EXPECT_TRUE(std::isnan(b.lifts[0].set_down));  // under way when the count stopped
  EXPECT_NEAR(b.lifts[1].lift_off, a.lifts[1].lift_off - 30.01, 1e-9);  // the new clock
  EXPECT_NEAR(b.k_q, a.k_q, 1e-12 * a.k_q);
  for (int i = 0; i < spots; ++i) {
    EXPECT_NEAR(b.hot_spots[i].damage, a.hot_spots[i].damage, 1e-12 * a.hot_spots[i].damage);
  }
  // A count saved twice reads back the same.
  saveUsageState(second.state(), file);
  const UsageState again = loadUsageState(file);
  const UsageState now = second.state();
  EXPECT_EQ(again.hours, now.hours);
  EXPECT_EQ(again.mass_ratio_cubed_sum, now.mass_ratio_cubed_sum);
  for (int i = 0; i < spots; ++i) {
    EXPECT_EQ(again.hot_spots[i].closed_damage, now.hot_spots[i].closed_damage);
    EXPECT_EQ(again.hot_spots[i].counter.turning_points, now.hot_spots[i].counter.turning_points);
    EXPECT_EQ(again.hot_spots[i].counter.pending, now.hot_spots[i].counter.pending);
  }
}

// The state of a count of rows 0 .. k1.
UsageState countedUntil(const CraneModel& m, int k1) {
  UsageCounter usage(m);
  LiftOffMonitor monitor;
  feed(m, usage, monitor, 0, k1, 0.0);
  return usage.state();
}

TEST(UsageCounter, AnotherMaxLoadRescalesTheCountedSpectrum) {
  const CraneModel m = liftOffModel();
  UsageState s = countedUntil(m, 3000);
  ASSERT_EQ(s.lift_count, 1);
  s.max_load = 2.0 * m.scene.crane->max_load;  // counted on a chart twice as strong
  s.mass_ratio_cubed_sum = std::pow(3600.0 / s.max_load, 3);
  const UsageCounter second(m, s);
  const double kq = std::pow(3600.0 / m.scene.crane->max_load, 3);
  EXPECT_NEAR(second.report().k_q, kq, 1e-12 * kq);
}

TEST(UsageCounter, ACountOfOtherHotSpotsIsRefusedByName) {
  const CraneModel m = liftOffModel();
  const UsageState counted = countedUntil(m, 100);
  UsageState renamed = counted;
  renamed.hot_spots[1].name = "boom_tip";
  try {
    UsageCounter c(m, renamed);
    FAIL() << "accepted a count of another hot spot";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'boom_tip'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("'mast_top'"), std::string::npos) << e.what();
  }
  UsageState recategorised = counted;
  recategorised.hot_spots[0].detail_category = 90.0;
  EXPECT_THROW(UsageCounter(m, recategorised), std::invalid_argument);
  UsageState fewer = counted;
  fewer.hot_spots.pop_back();
  try {
    UsageCounter c(m, fewer);
    FAIL() << "accepted a count of three hot spots";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("3 hot spots (mast_foot, mast_top, jib_root)"),
              std::string::npos)
        << e.what();
  }
}

TEST(UsageStore, AMalformedFileIsRefusedNamingTheKey) {
  const std::string file = ::testing::TempDir() + "usage_store_bad.yaml";
  const auto refuses = [&](const std::string& text, const std::string& key) {
    std::ofstream(file) << text;
    try {
      loadUsageState(file);
      ADD_FAILURE() << "accepted: " << text;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
    }
  };
  const std::string head = "hours: 1.0\nmax_load: 12500\nmass_ratio_cubed_sum: 0.1\n";
  refuses(head + "lifts: -1\n", "lifts");
  refuses("hours: .nan\nlifts: 1\nmax_load: 12500\nmass_ratio_cubed_sum: 0.1\n", "hours");
  refuses(head +
              "lifts: 1\nhot_spots:\n  - {name: a, detail_category: 71, closed_cycles_damage: 0.1, "
              "turning_points: [1, x], pending: []}\n",
          "turning_points");
  refuses(head +
              "lifts: 1\nhot_spots:\n  - {name: a, detail_category: 71, closed_cycles_damage: 0.1, "
              "turning_points: [], pending: [1, 2, 3]}\n",
          "pending");
  refuses(head + "lifts: 1\nlift: 3\n", "lift");
  EXPECT_THROW(loadUsageState(file + ".missing"), InputError);
}

}  // namespace
}  // namespace crane_twin
