// The twin's core (docs/twin.md), without ROS: a run continued from another's state, the
// forecast, the sway correction, the Kalman filter against closed forms, and the measured
// joint follower.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <future>
#include <random>

#include "crane_twin/drives/joint_tracking_filter.hpp"
#include "crane_twin/drives/measured_joint_follower.hpp"
#include "crane_twin/integrators/coupled_state.hpp"
#include "crane_twin/io/input_error.hpp"
#include "crane_twin/simulation/crane_simulation.hpp"
#include "crane_twin/simulation/invariant_reduced_simulation.hpp"
#include "crane_twin/simulation/simulation_capabilities.hpp"
#include "crane_twin/twin/payload_forecast.hpp"
#include "crane_twin/twin/sway_correction.hpp"
#include "crane_twin/twin/sway_estimator.hpp"

using namespace crane_twin;

namespace {
const std::string kScenes = std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/";

CraneModel live(std::vector<std::string> sets) {
  sets.insert(sets.begin(), {"rope.elements=40", "structure.modes=20"});
  return buildCraneModel(loadScene(kScenes + "t8036_live.yaml", sets));
}

CommandEntry moving() {
  CommandEntry c;
  c.slew_rate = 0.04;
  c.trolley_speed = -0.5;
  c.hoist_speed = -0.3;
  return c;
}
}  // namespace

TEST(ContinueFrom, ACopyWithTheSameStepRunsIdentically) {
  // Reduced, full order and pendulum: run A 2 s under motion, B (another instance) continues
  // from A; both run 3 s more under the same command: payloads equal to round-off.
  for (const char* model : {"rope.model=reduced", "rope.model=full", "rope.model=pendulum"}) {
    const CraneModel m = live({model, "initial.swing_deg=3"});
    std::unique_ptr<Simulation> a = makeSimulation(m), b = makeSimulation(m);
    a->initialize();
    b->initialize();
    a->setCommand(moving());
    for (int k = 0; k < 400; ++k) a->step();
    requireCapability<ContinuableRun>(*b).continueFrom(*a);
    EXPECT_EQ(b->time(), a->time());
    for (int k = 0; k < 600; ++k) {
      a->step();
      b->step();
    }
    EXPECT_LT((a->series().payload - b->series().payload).norm(), 1e-9) << model;
    EXPECT_NEAR(a->drives().trolleyRadius(), b->drives().trolleyRadius(), 1e-12) << model;
    EXPECT_NEAR(a->drives().hoistLength(), b->drives().hoistLength(), 1e-12) << model;
  }
  // A run cannot continue another rope model's state: said so.
  std::unique_ptr<Simulation> p = makeSimulation(live({"rope.model=pendulum"}));
  std::unique_ptr<Simulation> f = makeSimulation(live({"rope.model=full"}));
  p->initialize();
  f->initialize();
  EXPECT_THROW(requireCapability<ContinuableRun>(*p).continueFrom(*f), InputError);
  EXPECT_THROW(requireCapability<ContinuableRun>(*f).continueFrom(*p), InputError);
  // Nor a reduced rope's of another mesh or rigging.
  std::unique_ptr<Simulation> r = makeSimulation(live({"rope.model=reduced"}));
  r->initialize();
  for (const char* other : {"rope.elements=30", "hook.rigging_length=4"}) {
    std::unique_ptr<Simulation> o = makeSimulation(live({"rope.model=reduced", other}));
    o->initialize();
    EXPECT_THROW(requireCapability<ContinuableRun>(*r).continueFrom(*o), InputError) << other;
  }
}

// A reduced run whose off-centre landed start added its shapes to the basis (docs/model.md
// "Reduced rope": a landed start's shapes) is continued by a run whose own start, under the
// trolley, kept the scene's basis (the twin's forecast continues the twin so): the copy takes
// the adapted basis, and both run on identically through the drag and the lift-off.
TEST(ContinueFrom, ACopyOfAnOffCentreLandedRunTakesItsBasis) {
  const auto lift = [](const char* offset) {
    return buildCraneModel(loadScene(kScenes + "t8036_off_centre_lift.yaml",
                                     {"rope.elements=40", "structure.modes=20", offset}));
  };
  std::unique_ptr<Simulation> a = makeSimulation(lift("initial.payload_offset=[2, 0]"));
  std::unique_ptr<Simulation> b = makeSimulation(lift("initial.payload_offset=[0, 0]"));
  a->initialize();
  b->initialize();
  const auto shapes = [](const Simulation& s) {
    return dynamic_cast<const InvariantReducedSimulation&>(s).basis().shapes();
  };
  ASSERT_GT(shapes(*a), shapes(*b));
  for (int k = 0; k < 300; ++k) a->step();
  requireCapability<ContinuableRun>(*b).continueFrom(*a);
  EXPECT_EQ(shapes(*b), shapes(*a));
  for (int k = 0; k < 1500; ++k) {
    a->step();
    b->step();
  }
  EXPECT_EQ(a->statistics().full_order_steps, 0);
  EXPECT_LT((a->series().payload - b->series().payload).norm(), 1e-9);
}

TEST(SimulationCapabilities, EachRopeModelHasThoseItsTableNames) {
  // simulation_capabilities.hpp's table: continue, correct the motion, take a measured wind,
  // speculate.
  struct Row {
    std::vector<std::string> sets;
    bool continues, corrects, takes_wind, speculates;
  };
  const std::vector<Row> rows = {
      {{"rope.model=full"}, true, true, true, false},
      {{"rope.model=reduced"}, true, true, true, true},
      {{"rope.model=reduced", "rope.reduction=subdomains"}, false, false, false, true},
      {{"rope.model=pendulum"}, true, false, true, false},
  };
  for (const Row& r : rows) {
    std::unique_ptr<Simulation> sim = makeSimulation(live(r.sets));
    const std::string what = r.sets.back();
    EXPECT_EQ(capabilityOf<ContinuableRun>(*sim) != nullptr, r.continues) << what;
    EXPECT_EQ(capabilityOf<CorrectableMotion>(*sim) != nullptr, r.corrects) << what;
    EXPECT_EQ(capabilityOf<MeasuredWindInput>(*sim) != nullptr, r.takes_wind) << what;
    EXPECT_EQ(capabilityOf<SpeculativeRun>(*sim) != nullptr, r.speculates) << what;
    if (!r.continues) {
      // Asked for where it is missing: the message names the models that have it.
      try {
        requireCapability<ContinuableRun>(*sim);
        ADD_FAILURE() << what << ": no InputError";
      } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("pendulum"), std::string::npos) << e.what();
      }
      EXPECT_THROW(PayloadForecaster(live(r.sets), 0.0), InputError) << what;
    }
  }
}

TEST(PayloadForecast, ThePendulumForecastsItsOwnFuture) {
  // The cheapest rung forecasts too: at the twin's step the forecast is the twin's future.
  const CraneModel m = live({"rope.model=pendulum", "initial.swing_deg=4"});
  std::unique_ptr<Simulation> twin = makeSimulation(m);
  twin->initialize();
  for (int k = 0; k < 200; ++k) twin->step();
  const CommandEntry c = moving();
  PayloadForecaster same(m, 0.0);
  const PayloadForecast f = same.run(*twin, c, 10.0, 0.5);
  ASSERT_EQ(f.t.size(), 21u);
  twin->setCommand(c);
  for (size_t i = 0; i < f.t.size(); ++i) {
    while (twin->time() < f.t[i] - 1e-9) twin->step();
    EXPECT_LT((f.payload[i] - twin->series().payload).norm(), 1e-9) << "t " << f.t[i];
  }
  EXPECT_GT(f.max_swing, 0.1);
  EXPECT_FALSE(f.failed);
}

TEST(PayloadForecast, CancelStopsARunningForecastAndPrepareClearsIt) {
  // A forecast on another thread with a horizon it would take hours to reach stops once
  // cancelled (a twin shutting down does not wait for it); prepared again, it runs to its
  // horizon.
  const CraneModel m = live({"rope.model=pendulum", "initial.swing_deg=4"});
  std::unique_ptr<Simulation> twin = makeSimulation(m);
  twin->initialize();
  PayloadForecaster forecaster(m, 0.0);
  forecaster.prepare(*twin);
  const auto hold = [](double, const CraneDrives&) { return moving(); };
  std::future<PayloadForecast> job =
      std::async(std::launch::async, [&]() { return forecaster.runPrepared(hold, 1e7, 1.0); });
  while (job.wait_for(std::chrono::milliseconds(20)) != std::future_status::ready) {
    forecaster.cancel();
  }
  const PayloadForecast f = job.get();
  EXPECT_TRUE(f.cancelled);
  EXPECT_FALSE(f.failed);
  ASSERT_FALSE(f.t.empty());
  EXPECT_LT(f.t.back(), 1e7);
  forecaster.prepare(*twin);
  const PayloadForecast g = forecaster.runPrepared(hold, 2.0, 0.5);
  EXPECT_FALSE(g.cancelled);
  EXPECT_EQ(g.t.size(), 5u);
}

TEST(PayloadForecast, ForecastsATwinThatCameBackFromAStartAtFullOrder) {
  // A start the reduced rope does not carry (a payload on a rigging given its own velocity: its
  // bar loads or unloads the rope at once): the twin and the forecaster's copy both begin at full
  // order. Once the twin has handed back (reduced), the copy, which never integrated reduced,
  // continues it, and at the twin's step its forecast is the twin's future.
  const CraneModel m = live({"hook.rigging_length=2", "initial.payload_velocity=[0.3,0,0]"});
  std::unique_ptr<Simulation> twin = makeSimulation(m);
  twin->initialize();
  ASSERT_TRUE(twin->statistics().integrating_full_order);
  while (twin->statistics().integrating_full_order && twin->time() < 10.0) twin->step();
  ASSERT_FALSE(twin->statistics().integrating_full_order) << "no hand-back within 10 s";
  PayloadForecaster same(m, 0.0);
  const CommandEntry c = moving();
  const PayloadForecast f = same.run(*twin, c, 5.0, 0.5);
  twin->setCommand(c);
  for (size_t i = 0; i < f.t.size(); ++i) {
    while (twin->time() < f.t[i] - 1e-9) twin->step();
    EXPECT_LT((f.payload[i] - twin->series().payload).norm(), 1e-9) << "t " << f.t[i];
  }
}

TEST(PayloadForecast, AtTheTwinsStepItIsTheTwinsFutureAndAtTwiceTheStepClose) {
  const CraneModel m = live({"initial.swing_deg=4"});
  std::unique_ptr<Simulation> twin = makeSimulation(m);
  twin->initialize();
  for (int k = 0; k < 200; ++k) twin->step();
  const CommandEntry c = moving();
  PayloadForecaster same(m, 0.0), coarse(m, 0.01);
  const PayloadForecast f = same.run(*twin, c, 20.0, 0.5);
  const PayloadForecast g = coarse.run(*twin, c, 20.0, 0.5);
  ASSERT_EQ(f.t.size(), 41u);
  ASSERT_EQ(g.t.size(), 41u);
  // The twin itself continued under the command: the forecast at its own step is its future.
  twin->setCommand(c);
  double worst_coarse = 0.0;
  for (size_t i = 0; i < f.t.size(); ++i) {
    while (twin->time() < f.t[i] - 1e-9) twin->step();
    EXPECT_NEAR(g.t[i], f.t[i], 1e-9);
    EXPECT_LT((f.payload[i] - twin->series().payload).norm(), 1e-9) << "t " << f.t[i];
    worst_coarse = std::max(worst_coarse, (g.payload[i] - f.payload[i]).norm());
  }
  // 10 ms steps against 5 ms over 20 s of slewing, trolley travel and hoisting (with the
  // slewing inertial loads on, 20 ms steps were 1.7 cm off).
  EXPECT_LT(worst_coarse, 0.01);
  EXPECT_GT(f.max_swing, 0.5);
  EXPECT_FALSE(f.failed);
  EXPECT_THROW(same.run(*twin, c, 0.0, 0.5), std::invalid_argument);
}

TEST(SwayCorrection, MovesTheEndByDpAndGivesItDvRigidly) {
  const CraneModel m = live({"initial.swing_deg=2"});
  InvariantReducedSimulation sim(m);
  sim.initialize();
  for (int k = 0; k < 100; ++k) sim.step();
  const CoupledState before = sim.fullState();
  const int last = 6 * (sim.ropeNodes() - 1);
  const Eigen::Vector3d dp(0.3, -0.2, 0.0), dv(-0.05, 0.08, 0.0);
  CoupledState f = before;
  rotateRopeAboutTop(f.q, f.v, dp, dv);
  // The end moves by dp's part across the rope, to second order (the rope turns: |dp|^2 / L
  // lifts it), and its velocity gains dv's part across the rope.
  const Eigen::Vector3d rho = before.q.segment<3>(last) - before.q.head<3>();
  const double L = rho.norm();
  const Eigen::Vector3d n = rho / L, n_after = (f.q.segment<3>(last) - f.q.head<3>()) / L;
  const Eigen::Vector3d dp_across = dp - dp.dot(n) * n, dv_across = dv - dv.dot(n_after) * n_after;
  EXPECT_LT((f.q.segment<3>(last) - before.q.segment<3>(last) - dp_across).norm(),
            dp.squaredNorm() / L + 1e-9);
  const Eigen::Vector3d dv_got = f.v.segment<3>(last) - before.v.segment<3>(last);
  EXPECT_LT((dv_got - dv_got.dot(n_after) * n_after - dv_across).norm(), 1e-3 * dv.norm());
  // Rigid: every node keeps its distance to the top, the top stays.
  for (int j = 0; j < sim.ropeNodes(); ++j) {
    EXPECT_NEAR((f.q.segment<3>(6 * j) - f.q.head<3>()).norm(),
                (before.q.segment<3>(6 * j) - before.q.head<3>()).norm(), 1e-9);
  }
  EXPECT_LT((f.q.head<3>() - before.q.head<3>()).norm(), 1e-15);
  // Into the reduced run: the basis carries the rotation, so the payload lands where the
  // rotated rope puts it.
  const Eigen::Vector3d p0 = sim.series().payload;
  SwayUpdate u;  // the swing only: no structure modes
  u.position_correction = dp.head<2>();
  u.velocity_correction = dv.head<2>();
  applyTwinCorrection(sim, u, {});
  EXPECT_LT((sim.series().payload - f.q.segment<3>(last)).norm(), 1e-6);
  EXPECT_LT((sim.series().payload_velocity - f.v.segment<3>(last)).norm(), 1e-6)
      << sim.series().payload_velocity.transpose() << " vs " << f.v.segment<3>(last).transpose();
  EXPECT_GT((sim.series().payload - p0).norm(), 0.3);
  for (int k = 0; k < 50; ++k) sim.step();  // and it runs on
  EXPECT_TRUE(sim.series().payload.allFinite());
}

TEST(SwayEstimator, OneUpdateIsTheScalarKalmanGain) {
  // P0 = diag(s^2), one measurement: K = s^2 / (s^2 + r) on the position, 0 on the velocity.
  SwayEstimatorSettings set;
  set.initial_position_sigma = 1.0;
  set.measurement_noise = 0.5;
  SwayEstimator e(set);
  SwayModel pendulum;
  pendulum.length = 60.0;
  const SwayUpdate u = e.update(Eigen::Vector2d(1.0, -2.0), Eigen::Vector2d::Zero(), pendulum);
  ASSERT_TRUE(u.accepted);
  EXPECT_NEAR(u.position_correction.x(), 1.0 / 1.25, 1e-12);
  EXPECT_NEAR(u.position_correction.y(), -2.0 / 1.25, 1e-12);
  EXPECT_NEAR(u.velocity_correction.norm(), 0.0, 1e-12);
  EXPECT_NEAR(e.covariance(pendulum)(0, 0), 1.0 * 0.25 / 1.25, 1e-12);
  // An outlier beyond the gate is refused and changes nothing.
  const Eigen::MatrixXd P = e.covariance(pendulum);
  const SwayUpdate o = e.update(Eigen::Vector2d(100.0, 0.0), Eigen::Vector2d::Zero(), pendulum);
  EXPECT_FALSE(o.accepted);
  EXPECT_EQ(e.covariance(pendulum), P);
  // Ten refusals in a row: the filter re-acquires at its prior and takes the eleventh.
  for (int k = 1; k < SwayEstimator::kReacquireAfter; ++k)
    EXPECT_FALSE(e.update(Eigen::Vector2d(100.0, 0.0), Eigen::Vector2d::Zero(), pendulum).accepted);
  const SwayUpdate again = e.update(Eigen::Vector2d(3.0, 0.0), Eigen::Vector2d::Zero(), pendulum);
  EXPECT_TRUE(again.reacquired);
  EXPECT_TRUE(again.accepted);
  EXPECT_NEAR(again.position_correction.x(), 3.0 / 1.25, 1e-12);
  EXPECT_THROW(e.predict(-1.0), std::invalid_argument);
  set.measurement_noise = 0.0;
  EXPECT_THROW(SwayEstimator bad(set), std::invalid_argument);
}

TEST(SwayEstimator, LocksALinearPendulumOntoTheTruthFromNoisyMeasurements) {
  // Truth: a 62 m pendulum swinging 1.5 m in x and 0.8 m in y (closed form). The twin starts at
  // rest; 5 Hz measurements with 5 cm noise; between them both evolve by the same closed form.
  // After 30 s the twin is within 0.1 m, and its 1-sigma radius is consistent with that.
  const double g = 9.81, l = 62.0, w = std::sqrt(g / l), h = 0.2;
  auto propagate = [&](Eigen::Vector4d& x, double dt) {
    const double c = std::cos(w * dt), s = std::sin(w * dt);
    for (int a = 0; a < 2; ++a) {
      const double p = x[a], v = x[a + 2];
      x[a] = c * p + s / w * v;
      x[a + 2] = -w * s * p + c * v;
    }
  };
  Eigen::Vector4d truth(1.5, 0.0, 0.0, 0.8 * w), twin = Eigen::Vector4d::Zero();
  SwayEstimator e;
  SwayModel pendulum;
  pendulum.length = l;
  pendulum.gravity = g;
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.05);
  double worst_late = 0.0;
  for (int k = 1; k <= 300; ++k) {  // 60 s
    propagate(truth, h);
    propagate(twin, h);
    e.predict(h);
    const Eigen::Vector2d z = truth.head<2>() + Eigen::Vector2d(noise(rng), noise(rng));
    const SwayUpdate u = e.update(z, twin.head<2>(), pendulum);
    twin.head<2>() += u.position_correction;
    twin.tail<2>() += u.velocity_correction;
    if (k * h >= 30.0) worst_late = std::max(worst_late, (twin.head<2>() - truth.head<2>()).norm());
  }
  EXPECT_LT(worst_late, 0.1);
  EXPECT_LT(e.positionSigma(), 0.05);
  EXPECT_GT(e.positionSigma(), 0.001);
}

TEST(JointTrackingFilter, LagsAConstantAccelerationByItsClosedFormAndFollowsARateExactly) {
  // Noise-free samples at 100 Hz (omega T = 0.04). A constant rate: followed exactly once the
  // start (v = 0) has died out. A constant acceleration a: the continuous filter's steady
  // lag, a / omega^2 in position and sqrt(2) a / omega in rate (the file's comment), to the
  // sampling's O(omega T).
  const double omega = 4.0, T = 0.01, a = 0.5, v = 0.4;
  JointTrackingFilter rate_only(omega, false), accelerating(omega, false);
  for (int k = 0; k <= 2000; ++k) {  // 20 s: e^(-omega t / sqrt(2)) = 1e-25
    const double t = k * T;
    rate_only.add(t, 3.0 + v * t);
    accelerating.add(t, 0.5 * a * t * t);
  }
  const double t = 20.0;
  EXPECT_NEAR(rate_only.position(), 3.0 + v * t, 1e-9);
  EXPECT_NEAR(rate_only.rate(), v, 1e-9);
  const double lag = 0.5 * a * t * t - accelerating.position();
  const double rate_lag = a * t - accelerating.rate();
  EXPECT_NEAR(lag, a / (omega * omega), 0.05 * a / (omega * omega));
  EXPECT_NEAR(rate_lag, std::sqrt(2.0) * a / omega, 0.05 * std::sqrt(2.0) * a / omega);
}

TEST(JointTrackingFilter, PassesTheNoiseItsBandwidthSays) {
  // White noise sigma at 30 Hz on a joint at rest: the steady variances are the continuous
  // filter's, 3 / (2 sqrt(2)) omega T sigma^2 (position) and omega^3 T sigma^2 / (2 sqrt(2))
  // (rate), to the sampling's O(omega T) and the sample's statistics (60 000 samples,
  // correlated over about 1 / omega: some 2 % on a variance). An angle's innovations wrap: a
  // slew angle measured about pi is filtered about pi, not about 0.
  const double omega = 3.0, T = 1.0 / 30.0, sigma = 0.005;
  std::mt19937 rng(2);
  std::normal_distribution<double> noise(0.0, sigma);
  JointTrackingFilter f(omega, false), angle(omega, true);
  double sxx = 0.0, svv = 0.0, worst_angle = 0.0;
  int n = 0;
  for (int k = 0; k < 60000; ++k) {
    const double e = noise(rng);
    f.add(k * T, e);
    const double y = 3.14159265358979323846 + e;
    angle.add(k * T, std::atan2(std::sin(y), std::cos(y)));
    if (k > 300) {
      sxx += f.position() * f.position();
      svv += f.rate() * f.rate();
      ++n;
      worst_angle = std::max(worst_angle, std::abs(std::cos(angle.position()) + 1.0));
    }
  }
  const double pxx = 3.0 / (2.0 * std::sqrt(2.0)) * omega * T * sigma * sigma;
  const double pvv = omega * omega * omega * T * sigma * sigma / (2.0 * std::sqrt(2.0));
  EXPECT_NEAR(sxx / n, pxx, 0.15 * pxx);
  EXPECT_NEAR(svv / n, pvv, 0.15 * pvv);
  EXPECT_LT(worst_angle, 1e-3);
}

TEST(MeasuredJointFollower, ACraneAtRestStaysAtRestThroughItsEncodersNoise) {
  // The real crane stands; its encoders give 30 Hz samples with noise 1e-4 rad and 5 mm. The
  // model's drives (1 ms steps) stay within a few sigma of the truth, and the trolley's
  // acceleration is what the filter's rate passes (JointTrackingFilter: about omega^2 sigma =
  // 0.08 m/s^2, the position loop adding to it): under twice that. The raw samples and their
  // 0.5 s slope, passed through, made the drive ramp every sample's new rate at its limit
  // (0.40 m/s^2 RMS against the trolley's 0.5, the rope shaken).
  const Scene scene = loadScene(kScenes + "t8036_live.yaml", {"trolley.radius=30"});
  const CraneDescription& crane = *scene.crane;
  CraneDrives drives(scene);
  const JointFollowerSettings settings;
  MeasuredJointFollower follower(settings);
  std::mt19937 rng(9);
  std::normal_distribution<double> unit(0.0, 1.0);
  const Eigen::Vector3d truth(drives.slewAngle(), drives.trolleyRadius(), drives.hoistLength());
  const double dt = 0.001;
  double worst_trolley = 0.0, worst_hoist = 0.0, sum_a2 = 0.0;
  int n = 0;
  double last_speed = 0.0;
  for (int k = 0; k < 30000; ++k) {  // 30 s
    const double t = k * dt;
    if (k % 33 == 0) {
      JointSample s;
      s.t = t;
      s.position = truth + Eigen::Vector3d(1e-4 * unit(rng), 5e-3 * unit(rng), 5e-3 * unit(rng));
      ASSERT_EQ(follower.add(s, crane), "");
    }
    drives.setCommand(follower.command(t, drives, crane));
    drives.advance(t, dt);
    if (t > 5.0) {
      worst_trolley = std::max(worst_trolley, std::abs(drives.trolleyRadius() - truth.y()));
      worst_hoist = std::max(worst_hoist, std::abs(drives.hoistLength() - truth.z()));
      const double acc = (drives.trolleySpeed() - last_speed) / dt;
      sum_a2 += acc * acc;
      ++n;
    }
    last_speed = drives.trolleySpeed();
  }
  const double rms_acceleration = std::sqrt(sum_a2 / n);
  std::printf(
      "at rest through 5 mm noise: trolley within %.2f mm, hoist within %.2f mm, trolley "
      "acceleration RMS %.4f m/s^2\n",
      1e3 * worst_trolley, 1e3 * worst_hoist, rms_acceleration);
  EXPECT_LT(worst_trolley, 0.01);
  EXPECT_LT(worst_hoist, 0.01);
  const double omega = settings.tracking_bandwidth;
  EXPECT_LT(rms_acceleration, 2.0 * omega * omega * 5e-3);
}

TEST(MeasuredJointFollower, FollowsJitteryMeasurementsWithinTheDriveLimitsAndBridgesAGap) {
  // A crane accelerating at its drives' limits to 0.05 rad/s of slewing, 0.4 m/s of trolley
  // travel out and 0.1 m/s of hoisting, measured at 20 Hz with +-10 ms jitter, no velocities,
  // and a 1 s gap. The model's drives (5 ms steps) follow: after 5 s within 0.005 rad and 5 cm,
  // the gap included (bridged by extrapolation, flagged stale); never above the limits.
  const Scene scene = loadScene(kScenes + "t8036_live.yaml", {"trolley.radius=30"});
  const CraneDescription& crane = *scene.crane;
  CraneDrives drives(scene);
  MeasuredJointFollower follower;
  std::mt19937 rng(3);
  double worst_ramp = 0.0;
  std::uniform_real_distribution<double> jitter(-0.01, 0.01);
  // Speed v reached at acceleration a: x(t) = v t - v^2 / (2 a) after t = v / a.
  auto ramp = [](double t, double v, double a) {
    const double t1 = v / a;
    return t < t1 ? 0.5 * a * t * t : v * t - v * v / (2.0 * a);
  };
  auto real = [&](double t) {
    t = std::max(t, 0.0);
    return Eigen::Vector3d(ramp(t, 0.05, crane.slewing.max_acceleration),
                           30.0 + ramp(t, 0.4, crane.trolley.max_acceleration),
                           60.0 - ramp(t, 0.1, crane.hoist.max_acceleration));
  };
  const double dt = 0.005;
  double next_sample = 0.0, worst_slew = 0.0, worst_trolley = 0.0;
  bool stale_in_gap = false;
  for (int k = 0; k < 4000; ++k) {  // 20 s
    const double t = k * dt;
    if (t >= next_sample) {
      const bool gap = t > 10.0 && t < 11.0;
      if (!gap) {
        JointSample s;
        s.t = t;
        s.position = real(t + jitter(rng));
        EXPECT_EQ(follower.add(s, crane), "");
      }
      next_sample += 0.05;
    }
    if (t > 10.7 && t < 11.0) stale_in_gap |= follower.stale(t);
    drives.setCommand(follower.command(t, drives, crane));
    drives.advance(t, dt);
    EXPECT_LE(std::abs(drives.slewRate()), crane.slewing.max_speed + 1e-12);
    EXPECT_LE(std::abs(drives.trolleySpeed()), crane.trolley.max_speed + 1e-12);
    if (t <= 5.0) {
      worst_ramp = std::max(worst_ramp, std::abs(drives.trolleyRadius() - real(t + dt).y()));
    }
    if (t > 5.0) {
      worst_slew = std::max(worst_slew, std::abs(drives.slewAngle() - real(t + dt).x()));
      worst_trolley = std::max(worst_trolley, std::abs(drives.trolleyRadius() - real(t + dt).y()));
    }
  }
  std::printf(
      "jittery ramps and a gap: after 5 s slew within %.2f mrad, trolley within %.1f mm; "
      "trolley within %.1f mm while it accelerates\n",
      1e3 * worst_slew, 1e3 * worst_trolley, 1e3 * worst_ramp);
  EXPECT_LT(worst_slew, 0.005);
  EXPECT_LT(worst_trolley, 0.05);
  // While the trolley accelerates at a: the filter's steady lag a / omega^2 and the position
  // loop's, which makes up the filter's rate lag sqrt(2) a / omega at the gain g (the filter's
  // header and docs/twin.md "Following the crane").
  const JointFollowerSettings settings;
  const double omega = settings.tracking_bandwidth, a = crane.trolley.max_acceleration;
  EXPECT_LT(worst_ramp, a / (omega * omega) + std::sqrt(2.0) * a / (omega * settings.gain));
  EXPECT_TRUE(stale_in_gap);
  // Refused: NaN, out of order, off the rail.
  JointSample bad;
  bad.t = 100.0;
  bad.position = Eigen::Vector3d(0.0, std::nan(""), 30.0);
  EXPECT_NE(follower.add(bad, crane), "");
  bad.position = Eigen::Vector3d(0.0, 30.0, 30.0);
  bad.t = 1.0;
  EXPECT_NE(follower.add(bad, crane), "");
  bad.t = 100.0;
  bad.position.y() = 80.4;  // sensor noise at the limit: taken
  EXPECT_EQ(follower.add(bad, crane), "");
  bad.t = 101.0;
  bad.position.y() = 95.0;
  EXPECT_NE(follower.add(bad, crane).find("trolley radius"), std::string::npos);
  EXPECT_EQ(follower.refused(), 3);
}

TEST(Twin, LocksOntoARealCranesSwayAndForecastsIt) {
  // The rostest's scenario without ROS: the "real crane" (full order, 40 elements, 3900 kg,
  // released from 4 deg at azimuth 50 deg, slewing 0.03 rad/s and moving its trolley in at
  // 0.3 m/s from t = 1 s) and the twin (reduced rope, 3600 kg, at rest). The twin follows the
  // real joints (30 Hz, noise 1e-4 rad / 5 mm, no velocities) and 5 Hz payload positions with
  // 5 cm noise; the estimator carries the structure's sideways modes too (the real crane's jib
  // rings at 0.1 Hz after the release; the rope's swing alone left 0.55 m 10 s forecast errors).
  // After 30 s: estimate within 0.2 m; the 10 s forecasts within 0.3 m.
  const CraneModel real_model = live({"rope.model=full", "payload.mass=3900", "initial.swing_deg=4",
                                      "initial.swing_azimuth_deg=50"});
  const CraneModel twin_model = live({"rope.elements=120", "initial.swing_deg=0"});
  std::unique_ptr<Simulation> real = makeSimulation(real_model), twin = makeSimulation(twin_model);
  real->initialize();
  twin->initialize();
  MeasuredJointFollower follower;
  const std::vector<int> modes = swayCouplingModes(*twin);
  EXPECT_GE(modes.size(), 1u);  // the jib's sideways modes under 1 Hz
  SwayEstimator estimator(SwayEstimatorSettings{}, modeMotionNorms(*twin, modes));
  double nis = 0.0;
  int nis_n = 0;
  PayloadForecaster forecaster(twin_model, 0.02);
  std::mt19937 rng(11);
  std::normal_distribution<double> unit(0.0, 1.0);
  const CraneDescription& crane = *twin_model.scene.crane;
  CommandEntry cmd;
  cmd.slew_rate = 0.03;
  cmd.trolley_speed = -0.3;
  const double h = 0.005;
  std::vector<std::pair<double, PayloadForecast>> forecasts;
  std::vector<std::pair<double, Eigen::Vector3d>> truth;
  double worst_estimate = 0.0;
  for (int k = 1; k <= static_cast<int>(55.0 / h); ++k) {
    if (k == static_cast<int>(1.0 / h)) real->setCommand(cmd);
    real->step();
    const double t = real->time();
    if (k % 7 == 0) {  // ~30 Hz joint samples
      JointSample s;
      s.t = t;
      s.position = Eigen::Vector3d(real->drives().slewAngle() + 1e-4 * unit(rng),
                                   real->drives().trolleyRadius() + 5e-3 * unit(rng),
                                   real->drives().hoistLength() + 5e-3 * unit(rng));
      ASSERT_EQ(follower.add(s, crane), "");
    }
    twin->setCommand(follower.command(twin->time(), twin->drives(), crane));
    twin->step();
    estimator.predict(h);
    const Eigen::Vector3d p_real = real->series().payload;
    truth.emplace_back(t, p_real);
    if (k % 40 == 0) {  // 5 Hz payload measurements
      const Eigen::Vector2d z = p_real.head<2>() + 0.05 * Eigen::Vector2d(unit(rng), unit(rng));
      const SeriesValues row = twin->series();
      const SwayUpdate u =
          estimator.update(z, row.payload.head<2>(), swayModelAt(*twin, row, modes, 9.81));
      if (t > 30.0) {
        nis += u.normalized;
        ++nis_n;
      }
      if (u.accepted) {
        applyTwinCorrection(*twin, u, modes);
      }
    }
    if (t >= 30.0)
      worst_estimate = std::max(worst_estimate, (twin->series().payload - p_real).norm());
    if (t >= 30.0 && t <= 45.0 && k % 200 == 0) {
      const Eigen::Vector3d r = follower.holdRates(twin->time());
      CommandEntry held;
      held.slew_rate = r.x();
      held.trolley_speed = r.y();
      held.hoist_speed = r.z();
      forecasts.emplace_back(t, forecaster.run(*twin, held, 10.0, 0.5));
    }
  }
  EXPECT_LT(worst_estimate, 0.2);
  double worst_forecast = 0.0;
  for (const auto& [t0, f] : forecasts) {
    const double t10 = f.t.back();
    for (const auto& [t, p] : truth)
      if (std::abs(t - t10) < 1e-6)
        worst_forecast = std::max(worst_forecast, (f.payload.back() - p).norm());
  }
  std::printf(
      "twin: worst estimate after 30 s %.3f m, worst 10 s forecast %.3f m (%zu), "
      "mean NIS %.2f\n",
      worst_estimate, worst_forecast, forecasts.size(), nis / nis_n);
  EXPECT_LT(worst_forecast, 0.3);
}

TEST(SwayCorrection, AZeroCorrectionLeavesTheRunAsItWas) {
  // dp = dv = 0 repeated at 5 Hz on a slewing, travelling run: the payload path stays the
  // uncorrected run's (the reduced state is projected and its accelerations recomputed).
  const CraneModel m = live({"initial.swing_deg=4", "initial.swing_azimuth_deg=50"});
  std::unique_ptr<Simulation> a = makeSimulation(m), b = makeSimulation(m);
  a->initialize();
  b->initialize();
  a->setCommand(moving());
  b->setCommand(moving());
  double worst = 0.0;
  for (int k = 1; k <= 2000; ++k) {
    a->step();
    b->step();
    if (k % 40 == 0) applyTwinCorrection(*b, SwayUpdate{}, {});
    worst = std::max(worst, (a->series().payload - b->series().payload).norm());
  }
  std::printf("zero correction: worst payload difference %.3g m\n", worst);
  EXPECT_LT(worst, 1e-3);
}

TEST(TwinCorrection, MovesTheStructureModesAndTheRopeWithThem) {
  // A correction of the lowest sway-coupled modes alone: the trolley point and the payload
  // both move by Phi d_eta (the rope goes with its top), and the run goes on calmly.
  const CraneModel m = live({"initial.swing_deg=0"});
  InvariantReducedSimulation sim(m);
  sim.initialize();
  for (int k = 0; k < 100; ++k) sim.step();
  const std::vector<int> modes = swayCouplingModes(sim);
  ASSERT_GE(modes.size(), 1u);
  const SwayModel model = swayModelAt(sim, sim.series(), modes, 9.81);
  SwayUpdate u;
  u.structure_correction = Eigen::VectorXd::Zero(modes.size());
  u.structure_rate_correction = Eigen::VectorXd::Zero(modes.size());
  u.structure_correction[0] = 0.2 / model.phi.col(0).norm();  // 0.2 m at the trolley
  const SeriesValues before = sim.series();
  applyTwinCorrection(sim, u, modes);
  const SeriesValues after = sim.series();
  const Eigen::Vector2d expect = model.phi * u.structure_correction;
  EXPECT_LT(((after.trolley - before.trolley).head<2>() - expect).norm(), 1e-6);
  EXPECT_LT(((after.payload - before.payload).head<2>() - expect).norm(), 1e-3)
      << (after.payload - before.payload).transpose() << " vs " << expect.transpose();
  double worst = 0.0;
  for (int k = 0; k < 400; ++k) {
    sim.step();
    worst = std::max(worst, (sim.series().trolley - before.trolley).norm());
  }
  std::printf("after a 0.2 m structure correction: trolley moves at most %.3f m in 2 s\n", worst);
  EXPECT_LT(worst, 0.5);
}
