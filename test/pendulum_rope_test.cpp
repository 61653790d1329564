// The pendulum rope (rope.model: pendulum): its force and tangent against finite
// differences, its mass and statics against closed form, its swing and bounce frequencies
// against the closed form of a straight bar with an end mass, energy balance, the slack rope,
// hoisting, and agreement with the ANCF rope where the pendulum's assumptions hold.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "crane_twin/analysis/crane_snapshot.hpp"
#include "crane_twin/analysis/trajectory_compare.hpp"
#include "crane_twin/drives/crane_drives.hpp"
#include "crane_twin/io/config_reader.hpp"
#include "crane_twin/simulation/crane_simulation.hpp"
#include "crane_twin/simulation/pendulum_crane_simulation.hpp"
#include "period_estimate.hpp"

using namespace crane_twin;
using crane_twin_test::upCrossings;

namespace {
const std::string kDir = std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/";

// A 60 m rope with 3600 kg from a fixed anchor (the Chrono scene), as a pendulum.
CraneModel anchored(std::vector<std::string> sets) {
  sets.insert(sets.begin(), "rope.model=pendulum");
  return buildCraneModel(loadScene(kDir + "rope_pendulum_chrono.yaml", sets));
}

PendulumRope sampleRope() {
  return PendulumRope(60.0, 3.8, 4.4e7, 3600.0, Eigen::Vector3d(0, 0, -9.81), 250.0);
}

Vector6 tautState() {
  Vector6 q;
  q << 0.3, -0.2, 0.1, 2.0, 1.5, -60.05;  // l ~ 60.1 > 60
  return q;
}

}  // namespace

TEST(PendulumRope, ElasticForceAndTangentMatchFiniteDifferences) {
  const PendulumRope rope = sampleRope();
  const Vector6 q = tautState();
  Vector6 Q;
  Matrix6 K;
  rope.elasticForce(q, Q, &K);
  const double h = 1e-6;
  for (int i = 0; i < 6; ++i) {
    Vector6 qp = q, qm = q;
    qp(i) += h;
    qm(i) -= h;
    // Q = dU/dq.
    EXPECT_NEAR(Q(i), (rope.elasticEnergy(qp) - rope.elasticEnergy(qm)) / (2 * h), 1e-4 * Q.norm());
    Vector6 Qp, Qm;
    rope.elasticForce(qp, Qp);
    rope.elasticForce(qm, Qm);
    const Vector6 col = (Qp - Qm) / (2 * h);
    EXPECT_LT((col - K.col(i)).norm(), 1e-6 * K.norm()) << "column " << i;
  }
  // Slack: no force, no stiffness.
  Vector6 slack = q;
  slack.tail<3>() = q.head<3>() + Eigen::Vector3d(0, 0, -59.0);
  rope.elasticForce(slack, Q, &K);
  EXPECT_EQ(Q.norm(), 0.0);
  EXPECT_EQ(K.norm(), 0.0);
  EXPECT_EQ(rope.tension(slack), 0.0);
}

TEST(PendulumRope, WithoutTensionOnlyTheBarPushesBackInCompression) {
  PendulumRope rope = sampleRope();
  rope.setTensionOnly(false);
  Vector6 q = tautState();
  q.tail<3>() = q.head<3>() + Eigen::Vector3d(0, 0, -59.0);  // 1 m short
  EXPECT_NEAR(rope.tension(q), -4.4e7 / 60.0, 1e-6);
  Vector6 Q;
  Matrix6 K;
  rope.elasticForce(q, Q, &K);
  const double h = 1e-6;
  for (int i = 0; i < 6; ++i) {
    Vector6 qp = q, qm = q, Qp, Qm;
    qp(i) += h;
    qm(i) -= h;
    EXPECT_NEAR(Q(i), (rope.elasticEnergy(qp) - rope.elasticEnergy(qm)) / (2 * h), 1e-4 * Q.norm());
    rope.elasticForce(qp, Qp);
    rope.elasticForce(qm, Qm);
    EXPECT_LT(((Qp - Qm) / (2 * h) - K.col(i)).norm(), 1e-6 * K.norm()) << "column " << i;
  }
  EXPECT_NEAR(rope.elasticEnergy(q), 0.5 * 4.4e7 / 60.0, 1e-6);
}

TEST(PendulumRope, DampingForceIsLinearInVelocityAndDissipates) {
  const PendulumRope rope = sampleRope();
  const Vector6 q = tautState();
  Vector6 v;
  v << 0.1, 0.0, -0.2, -0.3, 0.4, 0.5;
  Vector6 Qd;
  Matrix6 C;
  rope.dampingForce(0.01, q, v, Qd, &C);
  EXPECT_LT((C * v - Qd).norm(), 1e-9 * Qd.norm());  // Q_d = C v exactly
  EXPECT_GT(v.dot(Qd), 0.0);                         // power taken out
  // A rigid translation stretches nothing: no damping force.
  Vector6 rigid;
  rigid << 1, 2, 3, 1, 2, 3;
  rope.dampingForce(0.01, q, rigid, Qd);
  EXPECT_LT(Qd.norm(), 1e-9);
}

TEST(PendulumRope, MassIsTheRopesAndTheEnds) {
  PendulumRope rope = sampleRope();
  for (double L : {60.0, 20.0}) {
    rope.setLength(L);
    // Sum of a rigid translation's inertia: mu L + m_top + m_end per direction.
    Vector6 ones;
    ones << 1, 0, 0, 1, 0, 0;
    EXPECT_NEAR(ones.dot(rope.massMatrix() * ones), 3.8 * L + 250.0 + 3600.0, 1e-9);
    // Total weight.
    EXPECT_NEAR(-(rope.gravityForce()(2) + rope.gravityForce()(5)), (3.8 * L + 3850.0) * 9.81,
                1e-6);
  }
  EXPECT_THROW(rope.setLength(0.0), std::invalid_argument);
  EXPECT_THROW(PendulumRope(60.0, 1.0, -1.0, 1.0, Eigen::Vector3d(0, 0, -9.81)),
               std::invalid_argument);
}

TEST(PendulumRope, StaticTensionIsTheHangingWeight) {
  PendulumCraneSimulation sim(anchored({"initial.mode=equilibrium", "initial.swing_deg=0"}));
  sim.initialize();
  const SeriesValues v = sim.series();
  const double W = (3600.0 + 1.9 * 60.0) * 9.81;
  EXPECT_NEAR(v.rope_top_tension, W, 1e-9 * W);
  // Stretched by the mean tension of the bar, (m_end + mu L / 2) g: l = L (1 + T / EA).
  EXPECT_NEAR(-v.payload.z(), 60.0 * (1.0 + (3600.0 + 57.0) * 9.81 / 2.2e7), 1e-9);
  // At rest: the first step does not move it.
  sim.step();
  EXPECT_LT(sim.state().v.norm(), 1e-9);
}

TEST(PendulumRope, SwingPeriodIsTheStraightBarsClosedForm) {
  // Rigid swing of a uniform bar with an end mass about its top:
  // w^2 = g (m_end + mu L / 2) / ((m_end + mu L / 3) l). Undamped scheme (rho_inf 1).
  PendulumCraneSimulation sim(anchored({"initial.mode=equilibrium", "initial.swing_deg=1",
                                        "integrator.rho_inf=1", "time_step=0.005", "duration=60"}));
  sim.initialize();
  const double l = (sim.state().q.tail<3>() - sim.state().q.head<3>()).norm();
  const double mu = 1.9 * 60.0, m = 3600.0;
  const double w = std::sqrt(9.81 * (m + mu / 2) / ((m + mu / 3) * l));
  std::vector<double> t, x;
  for (int k = 0; k < 12000; ++k) {
    sim.step();
    t.push_back(sim.time());
    x.push_back(sim.state().q(3));
  }
  const auto c = upCrossings(t, x);
  ASSERT_GE(c.size(), 3u);
  const double period = (c.back() - c.front()) / (c.size() - 1);
  EXPECT_NEAR(period, 2 * M_PI / w, 2e-4 * 2 * M_PI / w);
  std::printf("swing period %.5f s, closed form %.5f s\n", period, 2 * M_PI / w);
}

TEST(PendulumRope, BouncePeriodIsTheSpringsClosedForm) {
  // Released unstretched and hanging straight: the end bounces about the static stretch with
  // w^2 = (EA / L) / (m_end + mu L / 3) (the top fixed).
  PendulumCraneSimulation sim(anchored({"initial.mode=stress_free", "initial.swing_deg=0",
                                        "integrator.rho_inf=1", "time_step=0.0002"}));
  sim.initialize();
  const double w = std::sqrt(2.2e7 / 60.0 / (3600.0 + 1.9 * 60.0 / 3));
  const double zs = -60.0 * (1.0 + (3600.0 + 57.0) * 9.81 / 2.2e7);  // static end height
  std::vector<double> t, x;
  double lowest = 0.0;
  for (int k = 0; k < 10000; ++k) {
    sim.step();
    t.push_back(sim.time());
    x.push_back(sim.state().q(5) - zs);
    lowest = std::min(lowest, x.back());
  }
  const auto c = upCrossings(t, x);
  ASSERT_GE(c.size(), 3u);
  const double period = (c.back() - c.front()) / (c.size() - 1);
  EXPECT_NEAR(period, 2 * M_PI / w, 1e-4 * 2 * M_PI / w);
  // Amplitude = the static stretch (dropped from the unstretched length).
  EXPECT_NEAR(-lowest, -60.0 - zs, 1e-3 * (-60.0 - zs));
}

TEST(PendulumRope, EnergyIsConstantUndampedAndFallsWithDamping) {
  for (double c : {0.0, 0.01}) {
    PendulumCraneSimulation sim(
        anchored({"initial.swing_deg=10", "integrator.rho_inf=1", "time_step=0.002",
                  "rope.damping=" + std::to_string(c), "initial.payload_velocity=[0,0.5,0.2]"}));
    sim.initialize();
    const double e0 = sim.series().energy;
    double last = e0, drift = 0.0, above = 0.0;
    for (int k = 0; k < 10000; ++k) {
      sim.step();
      last = sim.series().energy;
      drift = std::max(drift, std::abs(last - e0));
      above = std::max(above, last - e0);
    }
    std::printf("c = %g s: energy drift %.3g J, above the start %.3g J, end - start %.4g J\n", c,
                drift, above, last - e0);
    if (c == 0.0) {
      EXPECT_LT(drift, 1e-6 * std::abs(e0)) << "undamped energy drift";
    } else {
      // The trapezoidal rule conserves a nonlinear spring's energy only to O(h^2) per swing, so
      // the damped energy may wiggle at that level, never above where it started.
      EXPECT_LT(above, 1e-9 * std::abs(e0)) << "damped energy rose above the start";
      EXPECT_LT(last, e0 - 1.0) << "damping took no energy";
    }
  }
}

TEST(PendulumRope, SlackThrowStaysFiniteAndSnapsTaut) {
  // The hard case: 12.5 t thrown up at 3 m/s on the T8036; the bar goes slack and snaps taut.
  PendulumCraneSimulation sim(buildCraneModel(
      loadScene(kDir + "hard_slack_throw.yaml", {"rope.model=pendulum", "duration=4"})));
  sim.initialize();
  double slackSteps = 0, peak = 0.0;
  for (int k = 0; k < 4000; ++k) {
    sim.step();
    const SeriesValues v = sim.series();
    ASSERT_TRUE(v.payload.allFinite());
    if (sim.rope().tension(sim.state().q) == 0.0) ++slackSteps;
    peak = std::max(peak, v.rope_top_tension);
    EXPECT_LT(v.constraint_error, 1e-9);
  }
  EXPECT_GT(slackSteps, 100);  // it did go slack
  const double W = (sim.rope().endMass() + sim.rope().massPerLength() * 60.0) * 9.81;
  EXPECT_GT(peak, 1.5 * W);  // and snapped taut
  std::printf("slack steps %.0f, peak tension %.1f kN (%.2f of the weight), halved steps %ld\n",
              slackSteps, peak / 1e3, peak / W, sim.statistics().halved_steps);
}

TEST(PendulumRope, HoistingConservesRopeMassAndTension) {
  // 60 m -> 20 m at 1 m/s (ramps of 2 s at 0.5 m/s^2: 1 + 38 + 1 m), then at rest: top tension
  // (m_end + mu L_new) g within 0.5 %.
  const CraneModel m = buildCraneModel(loadScene(
      kDir + "t8036_combination1.yaml",
      {"rope.model=pendulum", "structure.model=rigid", "initial.swing_deg=0", "time_step=0.01",
       "commands=[{t: 0, hoist_speed: -1.0}, {t: 40, hoist_speed: 0}]"}));
  PendulumCraneSimulation sim(m);
  sim.initialize();
  for (int k = 0; k < 6000; ++k) sim.step();
  const SeriesValues v = sim.series();
  EXPECT_NEAR(v.rope_length, 20.0, 1e-9);
  const double T = (m.end_mass + m.rope.mass_per_length * 20.0) * 9.81;
  // Still bouncing a little from the stop: average over a second.
  double mean = 0.0;
  for (int k = 0; k < 100; ++k) {
    sim.step();
    mean += sim.series().rope_top_tension / 100;
  }
  EXPECT_NEAR(mean, T, 0.005 * T);
}

TEST(PendulumRope, MatchesTheAncfRopeOnAPaperScene) {
  // Combination 1 (80 m, 3.6 t, 2.3 deg, modal structure) for 5 s: the payload barely bends
  // the rope, so the straight bar must follow the ANCF rope's payload closely.
  const std::vector<std::string> sets = {"rope.elements=30", "duration=5", "time_step=0.002",
                                         "structure.modes=20"};
  auto with = [&](const char* model) {
    std::vector<std::string> s = sets;
    s.push_back(std::string("rope.model=") + model);
    return buildCraneModel(loadScene(kDir + "t8036_combination1.yaml", s));
  };
  PendulumCraneSimulation pend(with("pendulum"));
  CraneSimulation full(with("full"));
  pend.initialize();
  full.initialize();
  double err = 0.0, swing = 0.0;
  const Eigen::Vector3d p0 = full.series().payload;
  for (int k = 0; k < 2500; ++k) {
    pend.step();
    full.step();
    err = std::max(err, (pend.series().payload - full.series().payload).norm());
    swing = std::max(swing, (full.series().payload - p0).norm());
  }
  std::printf("pendulum vs ANCF: payload error %.3g m (payload moved %.3g m)\n", err, swing);
  EXPECT_GT(swing, 1.0);
  EXPECT_LT(err, 0.01);  // budget: the 1 cm the ladder's rungs are held to
  // Sentinel: measured 1.95e-4 m (build/core/pendulum_rope_test, "pendulum vs ANCF").
  EXPECT_LT(err, 6e-4);
}

TEST(PendulumRope, SnapshotDrawsTheChord) {
  PendulumCraneSimulation sim(anchored({"initial.swing_deg=5"}));
  sim.initialize();
  SnapshotOptions o;
  o.samples_per_element = 8;
  const CraneSnapshot s = snapshotOf(sim, o);
  ASSERT_EQ(s.rope_curve.size(), 9u);
  EXPECT_LT((s.rope_curve.front() - sim.state().q.head<3>()).norm(), 1e-12);
  EXPECT_LT((s.hook.position - sim.state().q.tail<3>()).norm(), 1e-12);
  const Eigen::Vector3d up = (sim.state().q.head<3>() - sim.state().q.tail<3>()).normalized();
  EXPECT_NEAR((s.hook.orientation * Eigen::Vector3d::UnitZ()).dot(up), 1.0, 1e-12);
}

TEST(PendulumRope, MakeSimulationBuildsNoAncfRope) {
  const auto sim = makeSimulation(anchored({}));
  EXPECT_NE(dynamic_cast<PendulumCraneSimulation*>(sim.get()), nullptr);
  sim->initialize();
  EXPECT_EQ(sim->ropeNodes(), 2);
}

TEST(ResampleRope, InterpolatesAlongTheArcLength) {
  // A 2-node chord against a 5-node straight rope on the same line: no RMS error; shifted by
  // the chord's end moved 0.1 m sideways: the RMS of a linear ramp 0, 0.025, ..., 0.1.
  const std::vector<Eigen::Vector3d> chord = {{0, 0, 0}, {0, 0, -60}};
  const auto fine = resampleRopeAt(chord, {0.0, 0.25, 0.5, 0.75, 1.0});
  ASSERT_EQ(fine.size(), 5u);
  for (int j = 0; j < 5; ++j) EXPECT_LT((fine[j] - Eigen::Vector3d(0, 0, -15.0 * j)).norm(), 1e-12);
  Trajectory a, b;
  a.t = b.t = {0.0};
  a.payload = b.payload = a.cab = b.cab = a.jib_tip = b.jib_tip = {Eigen::Vector3d::Zero()};
  a.nodes = {chord};
  b.nodes = {fine};
  a.nodes[0][1].x() += 0.1;
  const ErrorMetrics m = compareTrajectories(a, b);
  const double expected = std::sqrt((0.025 * 0.025 + 0.05 * 0.05 + 0.075 * 0.075 + 0.01) / 5);
  EXPECT_NEAR(m.rope_rms_max, expected, 1e-12);
  EXPECT_THROW(resampleRopeAt({{0, 0, 0}}, {0.0, 1.0}), InputError);
  // A rigging: the pendulum's top, hook and payload (20 m of rope, 5 m of rigging) against 20
  // rope elements and the payload, the same straight chain: no error (interpolated by node
  // index instead, the RMS read 6.07 m).
  std::vector<Eigen::Vector3d> chain;
  for (int j = 0; j <= 20; ++j) chain.emplace_back(0, 0, -1.0 * j);
  chain.emplace_back(0, 0, -25.0);
  a.nodes = {{{0, 0, 0}, {0, 0, -20}, {0, 0, -25}}};
  b.nodes = {chain};
  EXPECT_LT(compareTrajectories(a, b).rope_rms_max, 1e-12);
  EXPECT_LT(compareTrajectories(b, a).rope_rms_max, 1e-12);
}

TEST(PendulumCrane, TheAncfSimulationRefusesAPendulumSceneByKey) {
  // makeSimulation picks PendulumCraneSimulation; CraneSimulation itself names the key it cannot
  // run, before it builds anything.
  try {
    CraneSimulation sim(anchored({}));
    FAIL() << "a pendulum scene was accepted by the ANCF simulation";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'rope.model'"), std::string::npos) << e.what();
  }
}
