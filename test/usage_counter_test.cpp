// What a run costs the crane (include/crane_twin/analysis/usage_counter.hpp, docs/fatigue.md
// "Usage"): lifts from the lift-off monitor, k_Q, and each hot spot's damage from its stress
// history streamed row by row, against the same history counted whole.
#include "crane_twin/analysis/usage_counter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "crane_twin/analysis/rainflow.hpp"
#include "crane_twin/io/scene.hpp"

namespace crane_twin {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(UsageCounter, LiftsKqAndTheDamageOfTheWholeHistory) {
  // 3.6 t on the T8036 (max_load 12.5 t, four hot spots on category 71): landed 2 s, lifted
  // at t = 2 (the tension at its static value), set down at t = 40, lifted again at t = 50
  // until the end at t = 100 s; the hot spots' stresses ring with slowly growing amplitudes.
  const CraneModel m = buildCraneModel(
      loadScene(std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/t8036_lift_off_slow.yaml",
                {"rope.elements=10"}));
  ASSERT_TRUE(m.hot_spots);
  const int spots = static_cast<int>(m.hot_spots->rows.size());
  UsageCounter usage(m);
  LiftOffMonitor lift_off;
  std::vector<std::vector<double>> history(spots);
  const double T = staticTopTension(m, 60.0);
  for (int k = 0; k <= 10000; ++k) {
    SeriesValues row;
    row.t = 0.01 * k;
    row.rope_length = 60.0;
    row.payload_landed = row.t < 2.0 || (row.t >= 40.0 && row.t < 50.0);
    row.rope_top_tension = row.payload_landed ? 0.1 * T : T;
    for (int i = 0; i < spots; ++i) {
      const double s = 1e6 * (i + 1) * (1.0 + 0.01 * row.t) * std::sin(2.0 * kPi * 0.3 * row.t);
      row.stresses.push_back(s);
      history[i].push_back(s);
    }
    lift_off.observe(row, T);
    usage.observe(row, lift_off);
  }
  const UsageReport r = usage.report();
  EXPECT_NEAR(r.hours, 100.0 / 3600.0, 1e-12);
  ASSERT_EQ(r.lifts.size(), 2u);
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

}  // namespace
}  // namespace crane_twin
