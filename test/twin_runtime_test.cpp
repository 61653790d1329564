// TwinRuntime (include/crane_twin/twin/twin_runtime.hpp): the twin's orchestration between steps
// without ROS: latency-compensated payload updates, the innovation gate, the correction applied
// to the simulation, the tension filter and the mass it implies, joint samples to the follower.
#include "crane_twin/twin/twin_runtime.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "crane_twin/io/scene.hpp"
#include "crane_twin/simulation/simulation.hpp"
#include "crane_twin/twin/timed_input_queue.hpp"

namespace crane_twin {
namespace {

const std::string kScenes = std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/";

CraneModel live(std::vector<std::string> sets) {
  sets.insert(sets.begin(), {"rope.elements=40", "structure.modes=20"});
  return buildCraneModel(loadScene(kScenes + "t8036_live.yaml", sets));
}

struct TwinRun {
  CraneModel model;
  std::unique_ptr<Simulation> sim;
  TwinRuntime runtime{SwayEstimatorSettings{}, JointFollowerSettings{}};
  std::vector<std::string> warnings;
  explicit TwinRun(std::vector<std::string> sets) : model(live(std::move(sets))) {
    sim = makeSimulation(model);
    sim->initialize();
    runtime.restart(model, *sim);
  }
  void step() {
    sim->step();
    runtime.afterStep(*sim, model.scene.time_step,
                      [this](const std::string& w) { warnings.push_back(w); });
  }
};

TEST(TwinRuntime, AMeasurementTakenEarlierIsComparedWithTheTwinThen) {
  // The swinging twin's own payload 0.2 s ago, p - v 0.2 (to first order), measured then:
  // accepted with an innovation of second order only.
  TwinRun r({"initial.swing_deg=3"});
  for (int k = 0; k < 200; ++k) r.step();
  const SeriesValues v = r.sim->series();
  const double age = 0.2;
  r.runtime.addPayload(r.sim->time() - age, v.payload - age * v.payload_velocity);
  r.step();
  ASSERT_EQ(r.runtime.payloadUpdates(), 1);
  EXPECT_TRUE(r.runtime.lastUpdate().accepted);
  // One step later the twin moved by v h: the innovation is that much, not v age.
  const double moved = v.payload_velocity.head<2>().norm() * r.model.scene.time_step;
  EXPECT_LT(r.runtime.lastUpdate().innovation.norm(), 2.0 * moved + 1e-6);
  EXPECT_GT(v.payload_velocity.head<2>().norm() * age, 10.0 * (2.0 * moved + 1e-6));
  EXPECT_TRUE(r.warnings.empty());
}

TEST(TwinRuntime, AnAcceptedMeasurementPullsTheTwinTowardItAndAFarOneIsRefused) {
  TwinRun r({});
  for (int k = 0; k < 20; ++k) r.step();
  const Eigen::Vector3d p = r.sim->series().payload;
  const Eigen::Vector3d z = p + Eigen::Vector3d(0.05, -0.03, 0.0);
  r.runtime.addPayload(r.sim->time(), z);
  r.step();
  ASSERT_EQ(r.runtime.payloadUpdates(), 1);
  EXPECT_EQ(r.runtime.correctionFailures(), 0);
  const Eigen::Vector3d after = r.sim->series().payload;
  EXPECT_LT((after - z).head<2>().norm(), 0.7 * (p - z).head<2>().norm());
  // 50 m away: beyond the gate, refused, said so, the twin untouched by it.
  const Eigen::Vector3d before = r.sim->series().payload;
  r.runtime.addPayload(r.sim->time(), before + Eigen::Vector3d(50.0, 0.0, 0.0));
  r.step();
  EXPECT_EQ(r.runtime.payloadUpdates(), 1);
  EXPECT_EQ(r.runtime.payloadRefused(), 1);
  ASSERT_FALSE(r.warnings.empty());
  EXPECT_NE(r.warnings.back().find("innovation gate"), std::string::npos) << r.warnings.back();
  EXPECT_LT((r.sim->series().payload - before).norm(), 0.05);
}

TEST(TwinRuntime, TheTensionFilterAndTheLoadCellFindTheLoadTheRopeCarries) {
  // A rope whose end carries 20 % more than the twin's, hanging from the start, the measured
  // tension U + 1.2 (T - U) with U = mu L g the rope's weight: the filtered ratio, and after one
  // 8 s window the end mass 1.2 m_e, offered once.
  TwinRun r({});
  r.step();
  EXPECT_FALSE(r.runtime.tensionSeen());
  EXPECT_DOUBLE_EQ(r.runtime.tensionRatio(), 1.0);
  EXPECT_DOUBLE_EQ(r.runtime.payloadMassEstimate(), r.model.scene.payload_mass);
  std::optional<double> offered;
  while (r.sim->time() < 9.0) {
    const SeriesValues v = r.sim->series();
    const double u = r.model.rope.mass_per_length * v.rope_length * r.model.scene.gravity;
    r.runtime.addTension(u + 1.2 * (v.rope_top_tension - u));
    r.step();
    if (const std::optional<double> m = r.runtime.takePayloadMass()) {
      EXPECT_FALSE(offered.has_value()) << "offered twice";
      offered = m;
    }
  }
  ASSERT_TRUE(r.runtime.tensionSeen());
  const double ratio = 1.0 + 0.2 * (1.0 - r.model.ropeMass() * r.model.scene.gravity /
                                              r.sim->series().rope_top_tension);
  EXPECT_NEAR(r.runtime.tensionRatio(), ratio, 0.01);
  const double expected = 1.2 * r.model.end_mass - r.model.scene.hookBlockMass();
  EXPECT_NEAR(r.runtime.payloadMassEstimate(), expected, 0.005 * expected);
  ASSERT_TRUE(offered.has_value());
  EXPECT_NEAR(*offered, expected, 0.005 * expected);
  EXPECT_FALSE(r.runtime.loadCell().landed());
}

TEST(TwinRuntime, JointSamplesReachTheFollowerAndABadOneIsRefused) {
  TwinRun r({});
  JointSample s;
  s.t = r.sim->time();
  s.position = Eigen::Vector3d(0.1, 40.0, 30.0);
  EXPECT_EQ(r.runtime.addJoints(s), "");
  EXPECT_TRUE(r.runtime.follower().hasSample());
  s.position.x() = std::nan("");
  EXPECT_NE(r.runtime.addJoints(s), "");
}

TEST(TwinRuntime, AStepBeforeRestartIsAnError) {
  TwinRuntime t{SwayEstimatorSettings{}, JointFollowerSettings{}};
  const CraneModel m = live({});
  std::unique_ptr<Simulation> sim = makeSimulation(m);
  sim->initialize();
  EXPECT_THROW(t.afterStep(*sim, 0.005, [](const std::string&) {}), std::logic_error);
  SwayEstimatorSettings bad;
  bad.gate = -1.0;
  EXPECT_THROW((TwinRuntime{bad, JointFollowerSettings{}}), std::invalid_argument);
}

TEST(TimedInputQueue, HoldsWhatTheTwinHasNotReachedAndReleasesItAtItsOwnTime) {
  // Measurements taken at 1.0, 1.2, 3.5 and 40 s (the last from a clock 40 s apart) and one
  // without a time, arriving in that order while the twin is at 1.1 s, with a 5 s horizon.
  TimedInputQueue<double> q(100);
  for (double t : {1.0, 1.2, 3.5}) q.push(t);
  std::vector<std::pair<double, double>> out;  // item, released at
  auto take = [&](double item, double at) { out.emplace_back(item, at); };
  auto time_of = [](double item) { return item; };
  q.release(1.1, 5.0, time_of, take);  // 1.0 due, 1.2 held (and 3.5 behind it)
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0], std::make_pair(1.0, 1.0));
  EXPECT_EQ(q.size(), 2u);
  q.release(3.0, 5.0, time_of, take);  // 1.2 due at its own time; 3.5 still ahead
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[1], std::make_pair(1.2, 1.2));
  q.push(40.0);
  q.push(NAN);
  q.release(3.6, 5.0, time_of, take);  // 3.5 at 3.5; 40 beyond the horizon and NaN: now
  ASSERT_EQ(out.size(), 5u);
  EXPECT_EQ(out[2], std::make_pair(3.5, 3.5));
  EXPECT_EQ(out[3], std::make_pair(40.0, 3.6));
  EXPECT_TRUE(std::isnan(out[4].first));
  EXPECT_EQ(out[4].second, 3.6);
  EXPECT_EQ(q.size(), 0u);
  // Full: the oldest goes, counted.
  TimedInputQueue<double> small(2);
  for (double t : {10.0, 11.0, 12.0}) small.push(t);
  EXPECT_EQ(small.dropped(), 1);
  out.clear();
  small.release(20.0, 5.0, time_of, take);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].first, 11.0);
  EXPECT_THROW(TimedInputQueue<double>(0), std::invalid_argument);
}

}  // namespace
}  // namespace crane_twin
