// Loads that land and lift off (docs/model.md "Ground contact", docs/scenes.md `ground:` and
// `initial.mode: landed`): the lift-off's dynamic factor against the closed form
// phi_2 = 1 + v_h sqrt(k / m) / g, a load at rest on the ground staying at rest, a set-down of the
// heaviest load penetrating under 1 cm and creating no energy, in the rope models that take a
// ground; the scene keys refused with the key named.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <memory>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "crane_twin/io/input_error.hpp"
#include "crane_twin/io/scene.hpp"
#include "crane_twin/rope/held_rope_equilibrium.hpp"
#include "crane_twin/simulation/crane_model.hpp"
#include "crane_twin/simulation/invariant_reduced_simulation.hpp"
#include "crane_twin/simulation/lift_off_monitor.hpp"
#include "crane_twin/simulation/simulation.hpp"
#include "crane_twin/simulation/step_tension_peak.hpp"
#include "crane_twin/simulation/supported_rope_simulation.hpp"
#include "crane_twin/structure/structure_support.hpp"

using namespace crane_twin;

namespace {

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The T8036 with a hoist that reaches its speed within millimetres (max_acceleration 20 m/s^2),
// so that the rope goes taut with the hoist at speed, as the closed form assumes.
std::string fastHoistCrane() {
  const std::string path = testing::TempDir() + "t8036_fast_hoist.yaml";
  std::string text = readFile(std::string(CRANE_TWIN_SOURCE_DIR) + "/config/cranes/t8036.yaml");
  text = std::regex_replace(text, std::regex("hoist: \\{max_speed: 1.0, max_acceleration: 0.5\\}"),
                            "hoist: {max_speed: 1.0, max_acceleration: 20.0}");
  EXPECT_NE(text.find("max_acceleration: 20.0"), std::string::npos);
  std::ofstream(path) << text;
  return path;
}

std::string writeScene(const std::string& name, const std::string& text) {
  const std::string path = testing::TempDir() + "ground_" + name + ".yaml";
  std::ofstream(path) << text;
  return path;
}

// A scene on the shipped T8036: its crane line and `body`.
std::string t8036Scene(const std::string& name, const std::string& body) {
  return writeScene(
      name, std::string("crane: ") + CRANE_TWIN_SOURCE_DIR + "/config/cranes/t8036.yaml\n" + body);
}

// The trolley point's height at rest for a scene (the rope's top).
double topHeight(const std::string& scene, const std::vector<std::string>& sets) {
  std::vector<std::string> s = sets;
  s.push_back("initial.mode=equilibrium");
  std::unique_ptr<Simulation> sim = makeSimulation(buildCraneModel(loadScene(scene, s)));
  sim->initialize();
  return sim->series().trolley.z();
}

// An independent linear model of a lift-off from a flexible structure: a massless rope spring k
// from the trolley to the load m, the trolley's vertical motion u = sum_i phi_i q_i from the
// structure's modes (unit modal mass, omega_i, damping terms 2 zeta omega_i, phi_i the mode's
// vertical displacement at the trolley),
//   q_i'' + 2 zeta omega_i q_i' + omega_i^2 q_i = -phi_i T,   T = max(0, k (v t - y + u)),
//   m y'' = T - m g once T reaches m g (y = 0 before),
// the hoist at speed v from the moment the rope is taut (t = 0, the structure at rest), by RK4 at
// 10 us (a step far under every kept period). Returns the peak T in `window` s after the lift-off.
double linearLiftOffPeak(const ModalStructureSupport& s, double k, double m, double g, double v,
                         double window) {
  const int n = s.size();
  Eigen::VectorXd phi(n);
  for (int i = 0; i < n; ++i) phi(i) = s.pointMotion(Eigen::VectorXd::Unit(n, i)).z();
  const Eigen::VectorXd& w2 = s.omega2();
  const Eigen::VectorXd& c = s.dampingTerms();
  // x = [q; q'; y; y'].
  bool lifted = false;
  const auto tension = [&](double t, const Eigen::VectorXd& x) {
    return std::max(0.0, k * (v * t - x(2 * n) + phi.dot(x.head(n))));
  };
  const auto rate = [&](double t, const Eigen::VectorXd& x) {
    Eigen::VectorXd d(2 * n + 2);
    const double T = tension(t, x);
    d.head(n) = x.segment(n, n);
    d.segment(n, n) = -c.cwiseProduct(x.segment(n, n)) - w2.cwiseProduct(x.head(n)) - phi * T;
    d(2 * n) = lifted ? x(2 * n + 1) : 0.0;
    d(2 * n + 1) = lifted ? T / m - g : 0.0;
    return d;
  };
  Eigen::VectorXd x = Eigen::VectorXd::Zero(2 * n + 2);
  const double h = 1e-5;
  double t = 0.0, t_lift = -1.0, peak = 0.0;
  while (t_lift < 0.0 || t < t_lift + window) {
    const Eigen::VectorXd k1 = rate(t, x), k2 = rate(t + h / 2, x + h / 2 * k1),
                          k3 = rate(t + h / 2, x + h / 2 * k2), k4 = rate(t + h, x + h * k3);
    x += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
    t += h;
    const double T = tension(t, x);
    if (!lifted && T >= m * g) {
      lifted = true;
      t_lift = t;
    }
    if (lifted) peak = std::max(peak, T);
    if (t > 100.0) break;  // never lifted: the caller's assertion reports it
  }
  return peak;
}

struct LandingRun {
  LiftOffMonitor monitor;
  StepTensionPeak peak;                     ///< the steps' top tension between the rows
  double lift_length = 0.0;                 ///< rope length at lift-off [m]
  double e_start = 0.0, e_max_after = 0.0;  ///< energy at the start; max after `quiet_from`
  double e_quiet = 0.0;                     ///< energy at the last row at or before quiet_from
  double max_penetration = 0.0;             ///< [m]
  double max_drift = 0.0;                   ///< payload's largest distance from its start [m]
  bool always_landed = true;
  double e_end = 0.0;  ///< energy at the last row
};

LandingRun run(const CraneModel& m, double quiet_from = 1e9) {
  std::unique_ptr<Simulation> sim = makeSimulation(m);
  sim->initialize();
  LandingRun r;
  const Scene& sc = m.scene;
  const double underside = sc.ground->height + sc.payload_height;
  const long steps = std::lround(sc.duration / sc.time_step);
  const long every = std::lround(sc.output_interval / sc.time_step);
  const Eigen::Vector3d p0 = sim->series().payload;
  r.e_start = sim->series().energy;
  r.e_max_after = -1e300;
  for (long k = 0; k <= steps; ++k) {
    if (k > 0) {
      sim->step();
      r.peak.addStep(sim->topTension());  // the factor crane_sim reports: every step's
    }
    if (k % every != 0) continue;
    const SeriesValues v = sim->series();
    EXPECT_TRUE(std::isfinite(v.energy) && v.payload.allFinite()) << "t = " << v.t;
    const int before = r.monitor.liftOffs();
    r.monitor.observe(v, staticTopTension(m, v.rope_length), r.peak.takeAtRow(v.rope_top_tension));
    if (r.monitor.liftOffs() > before) r.lift_length = v.rope_length;
    r.max_penetration = std::max(r.max_penetration, underside - v.payload.z());
    r.max_drift = std::max(r.max_drift, (v.payload - p0).norm());
    r.always_landed = r.always_landed && v.payload_landed;
    if (v.t <= quiet_from + 1e-9) r.e_quiet = v.energy;
    if (v.t >= quiet_from) r.e_max_after = std::max(r.e_max_after, v.energy);
    r.e_end = v.energy;
  }
  return r;
}

// phi_2 = 1 + v sqrt(k / m) / g with k the hook's axial stiffness n EA / (L + L_r / n) at the
// lift-off length, m the hanging point masses.
double closedFormPhi2(const CraneModel& m, double v, double L) {
  const double k = m.rope.axialStiffnessAt(L) / L;  // n EA L / (L + L_r / n), over L
  return 1.0 + v * std::sqrt(k / m.hangingPointMass()) / m.scene.gravity;
}

// The scene with `sets`, rope model `model` and a rope 3 cm longer than the distance from the
// rope's top at height `top` to the landed hook, reeled in at v_h from t = 0.
CraneModel liftOffModel(const std::string& scene, std::vector<std::string> sets,
                        const std::string& model, double v, double top) {
  sets.push_back("rope.model=" + model);
  const CraneModel probe = buildCraneModel(loadScene(scene, sets));
  const double d = top - (probe.scene.ground->height + probe.scene.payload_height);
  sets.push_back("rope.length=" + std::to_string(d + 0.03));
  std::ostringstream cmd;
  cmd << "commands=[{t: 0.0, hoist_speed: " << -v << "}]";
  sets.push_back(cmd.str());
  return buildCraneModel(loadScene(scene, sets));
}

}  // namespace

// A light rope (mass_per_length 0.019 kg/m per fall, 2.5 kg hanging) so that the closed form's
// massless rope is the model's: at the T8036's own 1.9 kg/m the rope's axial impedance
// sqrt(EA mu) v adds its own peak to the top tension (docs/model.md "Ground contact"). The
// snatch rings the light ANCF rope's axial element modes (kHz), whose crests the top tension
// carries and the closed form does not: a material damping of 1 ms (rope.damping, a damping
// ratio c omega / 2 = 0.5 % at the lift-off's 11 rad/s) takes them out.
TEST(GroundLanding, LiftOffFactorIsTheClosedFormWithAndWithoutReeving) {
  const std::string crane = fastHoistCrane();
  const std::string scene = writeScene("lift_off", "crane: " + crane + R"(
duration: 2.0
time_step: 0.001
output_interval: 0.002
structure: {model: rigid}
rope: {model: full, elements: 30, length: 60.0, damping: 0.001}
payload: {mass: 3600}
trolley: {radius: 30}
ground: {height: 0.0}
initial: {mode: landed}
)");
  for (const std::string reeving : {"0", "40"}) {
    const std::vector<std::string> base = {"rope.reeving_length=" + reeving};
    const double top = topHeight(scene, base);
    for (const std::string model : {"pendulum", "full"}) {
      for (double v : {0.5, 1.0}) {
        const CraneModel m = liftOffModel(scene, base, model, v, top);
        const LandingRun r = run(m);
        ASSERT_EQ(r.monitor.liftOffs(), 1) << model << " v " << v;
        const double expected = closedFormPhi2(m, v, r.lift_length);
        std::printf("%s, reeving %s m, v_h %.1f m/s: phi_2 %.4f, closed form %.4f (%+.2f %%)\n",
                    model.c_str(), reeving.c_str(), v, r.monitor.factor(), expected,
                    100.0 * (r.monitor.factor() / expected - 1.0));
        EXPECT_NEAR(r.monitor.factor(), expected, 0.03 * expected) << model << " v " << v;
      }
    }
  }
}

// A lift-off that throws its load while the hoist reels on: 4.4 t on four falls of the rigid
// T8036 at 1 m/s (phi_2 about 2.4, above 2, so the rope slackens after the snatch and the load
// bounces on it), the first 12 s of the pick-and-place at 30 elements, full order. Every step
// through a slack/taut switch is energy-consistent; while hoisting, generalized-alpha used to
// restart after each such step from consistent accelerations that carry the rope's unresolved
// axial modes (docs/model.md "Energy-consistent step"), and each restart raised the energy, which
// the hoist's pull on the bouncing rope then fed: at 1 ms the load climbed 1.6 m above its path
// at a quarter of the step within 12 s (3.4 m at 60 elements, and at 90 elements Newton failed at
// 9.2 s). The switching episode now runs on while hoisting, as at rest: the 1 ms path is within
// 6.3 cm of the quarter step's (the bouncing is not converged in the step below that: the
// unconverged snatch of the known limits, README).
TEST(GroundLanding, ABouncingLiftOffWhileHoistingConvergesWithTheStep) {
  const auto path = [](const std::string& dt) {
    const CraneModel m = buildCraneModel(loadScene(
        std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/t8036_pick_and_place.yaml",
        {"structure.model=rigid", "rope.falls=4", "payload.mass=4434", "trolley.radius=19",
         "rope.model=full", "rope.elements=30", "duration=12", "time_step=" + dt}));
    std::unique_ptr<Simulation> sim = makeSimulation(m);
    sim->initialize();
    std::vector<Eigen::Vector3d> p;  // every 10 ms
    const long steps = std::lround(m.scene.duration / m.scene.time_step);
    const long every = std::lround(0.01 / m.scene.time_step);
    for (long k = 1; k <= steps; ++k) {
      sim->step();
      if (k % every == 0) p.push_back(sim->series().payload);
    }
    return p;
  };
  const std::vector<Eigen::Vector3d> a = path("0.001"), b = path("0.00025");
  ASSERT_EQ(a.size(), b.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, (a[i] - b[i]).norm());
  std::printf(
      "bouncing lift-off while hoisting: payload at 1 ms within %.3g m of 0.25 ms; end "
      "heights %.3f and %.3f m\n",
      worst, a.back().z(), b.back().z());
  EXPECT_LT(worst, 0.1);
}

// On the T8036 the hook's stiffness is the rope's in series with the structure's vertical
// compliance at the trolley, c_s = (D K_z^-1 D^T)_zz of the modal structure (the jib and the
// mast bending under the hook load): phi_2 = 1 + v_h sqrt(k / m) / g with
// 1 / k = (L + L_r / n) / (n EA) + c_s. That closed form takes the structure as a massless
// spring; the T8036's lowest modes (0.10 to 0.78 Hz, `crane_sim modes --part structure`) are
// not faster than the lift-off's 0.96 Hz, so it holds where the tension builds slowly: within 5 %
// at 0.1 m/s (2.7 s from slack to lift-off); at 0.2 and 0.5 m/s the structure's own swing under
// the tension ramp moves phi_2 by -6 and +12 % (printed, docs/model.md "Ground contact").
// On the T8036 the series closed form (the structure's static compliance at the trolley in series
// with the rope) holds where the tension builds slowly against the structure's lowest modes; at
// 0.2 and 0.5 m/s the structure swings under the ramp (-6 and +12 % from it). The linear model
// with the structure's 100 modes (linearLiftOffPeak) gives the simulated factor at every speed.
TEST(GroundLanding, T8036LiftOffFactorIsTheSeriesStiffnessFormWithTheStructuresInertia) {
  const std::string crane = fastHoistCrane();
  const std::string scene = writeScene("lift_off_t8036", "crane: " + crane + R"(
duration: 6.0
time_step: 0.001
output_interval: 0.002
structure: {model: modal, modes: 100, damping_ratio: 0.01}
rope: {model: full, elements: 30, length: 60.0, damping: 0.001}
payload: {mass: 3600}
trolley: {radius: 30}
ground: {height: 0.0}
initial: {mode: landed}
)");
  // The undeformed support's point (the landed start sinks it by the trolley's and the rope's
  // weight: a few cm more slack).
  const CraneModel base = buildCraneModel(loadScene(scene));
  std::unique_ptr<RopeSupport> base_support = makeRopeSupport(base);
  base_support->setPose(0.0, base.scene.trolley_radius);
  const double top = base_support->point(Eigen::VectorXd::Zero(base_support->size())).z();
  for (const std::string model : {"pendulum", "full"}) {
    for (double v : {0.1, 0.2, 0.5}) {
      const CraneModel m = liftOffModel(scene, {}, model, v, top);
      std::unique_ptr<RopeSupport> support = makeRopeSupport(m);
      support->setPose(0.0, m.scene.trolley_radius);
      const double cs = support->setIterationWeights(0.0, 0.0, 1.0)(2, 2);
      const LandingRun r = run(m);
      ASSERT_EQ(r.monitor.liftOffs(), 1) << model << " v " << v;
      const double L = r.lift_length;
      const double k = 1.0 / (L / m.rope.axialStiffnessAt(L) + cs);
      const double expected = 1.0 + v * std::sqrt(k / m.hangingPointMass()) / m.scene.gravity;
      // The linear model with the structure's 100 modes (its inertia, which the series closed
      // form leaves out); the rope's weight W_r static at the top.
      const double g = m.scene.gravity, W_r = m.rope.mass_per_length * L * g;
      const double peak =
          linearLiftOffPeak(dynamic_cast<const ModalStructureSupport&>(*support),
                            m.rope.axialStiffnessAt(L) / L, m.hangingPointMass(), g, v, 3.0);
      const double linear = (peak + W_r) / (m.hangingPointMass() * g + W_r);
      std::printf(
          "T8036 %s, v_h %.1f m/s: structure %.3g m/N, rope %.3g m/N: phi_2 %.4f, "
          "closed form %.4f (%+.2f %%), linear model with the structure's modes %.4f "
          "(%+.2f %%)\n",
          model.c_str(), v, cs, L / m.rope.axialStiffnessAt(L), r.monitor.factor(), expected,
          100.0 * (r.monitor.factor() / expected - 1.0), linear,
          100.0 * (r.monitor.factor() / linear - 1.0));
      if (v == 0.1) {
        EXPECT_NEAR(r.monitor.factor(), expected, 0.05 * expected) << model << " v " << v;
      }
      EXPECT_NEAR(r.monitor.factor(), linear, 0.02 * linear) << model << " v " << v;
    }
  }
}

// The load landed at rest, 0.7 m of rope lying on it, no command: it stays where it is, and
// the energy never rises after the structure's first steps (the modal structure's start
// exchanges 0.1 J of 1 MJ in its first step, with or without a ground; the rigid structure's
// none).
TEST(GroundLanding, LoadAtRestStaysAtRest) {
  const std::string scene = writeScene("rest", std::string("crane: ") + CRANE_TWIN_SOURCE_DIR +
                                                   R"(/config/cranes/t8036.yaml
duration: 3.0
time_step: 0.001
output_interval: 0.01
structure: {model: modal, modes: 20}
rope: {model: full, elements: 30, length: 66.0}
payload: {mass: 3600}
trolley: {radius: 30}
ground: {height: 0.0}
initial: {mode: landed}
)");
  for (const std::string model : {"full", "pendulum", "reduced"}) {
    const CraneModel m = buildCraneModel(loadScene(scene, {"rope.model=" + model}));
    const LandingRun r = run(m, 0.1);
    std::printf("%s: drift %.3g m, energy rise %.3g J\n", model.c_str(), r.max_drift,
                r.e_max_after - r.e_start);
    EXPECT_TRUE(r.always_landed) << model;
    EXPECT_LT(r.max_drift, 1e-3) << model;
    EXPECT_LE(r.e_max_after, r.e_quiet + 1e-9 * std::abs(r.e_quiet) + 1e-6) << model;
    EXPECT_EQ(r.monitor.liftOffs(), 0) << model;
  }
}

// The heaviest shipped load (12.5 t) lowered at full hoist speed onto the ground: under 1 cm of
// penetration; once the hoist stops, the energy never rises.
TEST(GroundLanding, SetDownOfTheHeaviestLoadPenetratesUnderOneCentimetre) {
  const std::string scene = writeScene("set_down", std::string("crane: ") + CRANE_TWIN_SOURCE_DIR +
                                                       R"(/config/cranes/t8036.yaml
duration: 6.0
time_step: 0.001
output_interval: 0.005
structure: {model: modal, modes: 20}
rope: {model: full, elements: 30, length: 60.0}
payload: {mass: 12500}
trolley: {radius: 30}
ground: {height: 0.0}
initial: {mode: equilibrium}
commands:
  - {t: 0.0, hoist_speed: 1.0}
  - {t: 4.0, hoist_speed: 0.0}
)");
  const double top = topHeight(scene, {});
  for (const std::string model : {"full", "pendulum", "reduced"}) {
    const CraneModel probe = buildCraneModel(loadScene(scene, {"rope.model=" + model}));
    // The load's underside 2.5 m above the ground at rest: landed after about 3 s of lowering.
    const double L = top - probe.scene.payload_height - 2.5;
    const CraneModel m = buildCraneModel(
        loadScene(scene, {"rope.model=" + model, "rope.length=" + std::to_string(L)}));
    const LandingRun r = run(m, 4.5);
    std::printf("%s: max penetration %.4g m, energy after the hoist stops %.6g .. end %.6g J\n",
                model.c_str(), r.max_penetration, r.e_max_after, r.e_end);
    EXPECT_GT(r.max_penetration, 0.0) << model;   // it landed
    EXPECT_EQ(r.monitor.liftOffs(), 0) << model;  // a set-down is no lift
    EXPECT_LT(r.max_penetration, 0.01) << model;
    // From 4.5 s on (hoist at rest): never above the energy at 4.5 s.
    EXPECT_LE(r.e_max_after, r.e_quiet + 1e-9 * std::abs(r.e_quiet) + 1e-6) << model;
  }
}

// The monitor on synthetic rows: a bounce (off the ground for 0.2 s) is no lift and carries no
// factor; a lift counts once 0.5 s off the ground with the hoist reeling in, its factor the peak
// tension over the static one in the window, the rows before its confirmation included; a
// landing ends the window; a load thrown up without the hoist reeling in is no lift.
TEST(GroundLanding, LiftOffMonitorCountsLiftsNotBounces) {
  LiftOffMonitor mon(3.0);
  // The rope: 60 m until the hoist reels in at 0.1 m/s from t = 2 s.
  auto row = [&](double t, bool landed, double tension, double length = -1.0) {
    SeriesValues v;
    v.t = t;
    v.payload_landed = landed;
    v.rope_top_tension = tension;
    v.rope_length = length >= 0.0 ? length : 60.0 - 0.1 * std::max(0.0, t - 2.0);
    mon.observe(v, 1000.0);
  };
  for (double t = 0.0; t < 1.0; t += 0.01) row(t, true, 500.0);
  for (double t = 1.0; t < 1.2; t += 0.01) row(t, false, 1900.0);  // a bounce at 1.9
  EXPECT_EQ(mon.liftOffs(), 0);
  for (double t = 1.2; t < 2.0; t += 0.01) row(t, true, 800.0);
  EXPECT_EQ(mon.liftOffs(), 0);
  EXPECT_EQ(mon.factor(), 0.0);
  EXPECT_EQ(mon.warningFor(1.2), 0);
  row(2.0, false, 1100.0);
  row(2.1, false, 1450.0);  // the peak, before the confirmation
  EXPECT_EQ(mon.liftOffs(), 0);
  for (double t = 2.2; t < 2.6; t += 0.01) row(t, false, 1200.0);
  EXPECT_EQ(mon.liftOffs(), 1);
  EXPECT_DOUBLE_EQ(mon.factor(), 1.45);
  EXPECT_DOUBLE_EQ(mon.lastLiftOffTime(), 2.0);
  EXPECT_EQ(mon.warningFor(1.4), kLiftOffOverDesignFactor);
  EXPECT_EQ(mon.warningFor(1.5), 0);
  for (double t = 2.6; t < 6.0; t += 0.01) row(t, false, 1300.0);
  EXPECT_FALSE(mon.measuring());
  row(6.0, false, 5000.0);  // after the window: not a lift-off's peak
  EXPECT_DOUBLE_EQ(mon.factor(), 1.45);
  // Set down on 59.6 m of rope; the hoist stopped, the jib's rebound throws the load up for a
  // second: no lift (the hoist did not reel in).
  for (double t = 6.1; t < 7.0; t += 0.01) row(t, true, 300.0, 59.6);
  for (double t = 7.0; t < 8.0; t += 0.01) row(t, false, 1200.0, 59.6);
  EXPECT_EQ(mon.liftOffs(), 1);
  // It lands again; the hoist pays out 0.5 m, then reels in at 0.1 m/s: the load leaves the
  // ground at 13.5 s and counts 0.5 s later.
  for (double t = 8.0; t < 9.0; t += 0.01) row(t, true, 300.0, 59.6 + 0.5 * (t - 8.0));
  for (double t = 9.0; t < 13.5; t += 0.01) row(t, true, 300.0, 60.1 - 0.1 * (t - 9.0));
  for (double t = 13.5; t < 14.0; t += 0.01) row(t, false, 1100.0, 60.1 - 0.1 * (t - 9.0));
  EXPECT_EQ(mon.liftOffs(), 1);
  row(14.01, false, 1100.0, 60.1 - 0.1 * 5.01);
  EXPECT_EQ(mon.liftOffs(), 2);
  EXPECT_NEAR(mon.lastLiftOffTime(), 13.5, 1e-9);
  EXPECT_THROW(LiftOffMonitor(0.2), std::invalid_argument);
}

// A lifted load that touches the ground again for a moment while the hoist reels in (the jib's
// bounce under a load that had only just left the ground) is still the same lift: no set-down,
// no second lift. Lying kConfirmation, it is set down, dated at its landing; a new reel-in then
// lifts anew.
TEST(GroundLanding, LiftOffMonitorTakesATouchForPartOfTheLift) {
  LiftOffMonitor mon(3.0);
  auto row = [&](double t, bool landed, double length) {
    SeriesValues v;
    v.t = t;
    v.payload_landed = landed;
    v.rope_top_tension = 1000.0;
    v.rope_length = length;
    mon.observe(v, 1000.0);
  };
  auto reeled = [](double t) { return 60.0 - 0.1 * std::max(0.0, t - 1.0); };
  for (int k = 0; k < 200; ++k) row(0.01 * k, true, reeled(0.01 * k));  // landed to 2 s
  for (int k = 200; k < 300; ++k) row(0.01 * k, false, reeled(0.01 * k));
  EXPECT_EQ(mon.liftOffs(), 1);
  EXPECT_TRUE(mon.liftInProgress());
  for (int k = 300; k < 302; ++k) row(0.01 * k, true, reeled(0.01 * k));  // a 20 ms touch
  for (int k = 302; k < 600; ++k) row(0.01 * k, false, reeled(0.01 * k));
  EXPECT_EQ(mon.liftOffs(), 1);
  EXPECT_EQ(mon.setDowns(), 0);
  EXPECT_TRUE(mon.liftInProgress());
  // Lowered onto the ground at 6 s on 59.6 m of rope: set down 0.5 s later, dated 6 s.
  for (int k = 600; k < 649; ++k) row(0.01 * k, true, 59.6);
  EXPECT_EQ(mon.setDowns(), 0);
  row(6.49, true, 59.6);
  row(6.5, true, 59.6);
  EXPECT_EQ(mon.setDowns(), 1);
  EXPECT_FALSE(mon.liftInProgress());
  EXPECT_DOUBLE_EQ(mon.landingTime(), 6.0);
  // Reeled in again: a new lift once off the ground for 0.5 s.
  for (int k = 651; k < 750; ++k) row(0.01 * k, true, 59.6 - 0.1 * (0.01 * k - 6.5));
  for (int k = 750; k < 802; ++k) row(0.01 * k, false, 59.6 - 0.1 * (0.01 * k - 6.5));
  EXPECT_EQ(mon.liftOffs(), 2);
  EXPECT_NEAR(mon.lastLiftOffTime(), 7.5, 1e-9);
}

TEST(GroundLanding, LiftOffMonitorTakesTheStepsPeakBetweenRows) {
  // Rows every 10 ms, steps every 1 ms: a crest between two rows is the lift's peak.
  LiftOffMonitor rows_only(3.0), with_steps(3.0);
  StepTensionPeak peak;
  auto row = [&](double t, bool landed, double length, double row_tension) {
    SeriesValues v;
    v.t = t;
    v.payload_landed = landed;
    v.rope_top_tension = row_tension;
    v.rope_length = length;
    rows_only.observe(v, 1000.0);
    with_steps.observe(v, 1000.0, peak.takeAtRow(row_tension));
  };
  auto reeled = [](double t) { return 60.0 - 0.1 * t; };
  for (int k = 0; k < 100; ++k) row(0.01 * k, true, reeled(0.01 * k), 900.0);  // landed to 1 s
  peak.addStep(5000.0);  // a crest while the load lies: before the lift-off's row, not the lift's
  row(1.0, true, reeled(1.0), 950.0);
  for (int k = 101; k < 200; ++k) {
    // A ringing tension whose crests (2300 N) fall between the rows (1500 N at the rows).
    for (int j = 1; j < 10; ++j) peak.addStep(j == 5 ? 2300.0 : 1500.0);
    row(0.01 * k, false, reeled(0.01 * k), 1500.0);
  }
  ASSERT_EQ(rows_only.liftOffs(), 1);
  ASSERT_EQ(with_steps.liftOffs(), 1);
  EXPECT_DOUBLE_EQ(rows_only.factor(), 1.5);
  EXPECT_DOUBLE_EQ(with_steps.factor(), 2.3);
  // The peak is the row's own where no step was larger, and each row starts a new interval.
  EXPECT_DOUBLE_EQ(peak.takeAtRow(700.0), 700.0);
  peak.addStep(800.0);
  EXPECT_DOUBLE_EQ(peak.takeAtRow(700.0), 800.0);
  EXPECT_DOUBLE_EQ(peak.takeAtRow(600.0), 600.0);
}

TEST(GroundLanding, BadKeysAreRefusedWithTheKeyNamed) {
  const std::string crane = std::string(CRANE_TWIN_SOURCE_DIR) + "/config/cranes/t8036.yaml";
  const std::string base = "crane: " + crane + R"(
duration: 1.0
time_step: 0.001
structure: {model: rigid}
rope: {model: full, elements: 10, length: 60.0}
payload: {mass: 3600}
trolley: {radius: 30}
)";
  // Each case: overrides of the base scene, and the key the message must name.
  auto refused = [&](const std::vector<std::string>& sets, const std::string& key) {
    const std::string path = writeScene("bad", base);
    try {
      const CraneModel m = buildCraneModel(loadScene(path, sets));
      std::unique_ptr<Simulation> sim = makeSimulation(m);
      sim->initialize();
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
      return;
    }
    ADD_FAILURE() << "accepted: " << sets.front();
  };
  refused({"initial.mode=landed"}, "initial.mode");
  refused({"ground.height=0", "initial.mode=landed", "initial.swing_deg=3"}, "initial.swing_deg");
  refused({"initial.payload_offset=[1, 0]"}, "initial.payload_offset");
  refused({"ground.stiffness=-1"}, "ground.stiffness");
  refused({"ground.friction=3"}, "ground.friction");
  refused({"ground.damping_ratio=-0.1"}, "ground.damping_ratio");
  refused({"ground.grip=1"}, "ground.grip");
  refused({"payload.height=-2"}, "payload.height");
  // A rope too short to reach the landed load: the key and both distances named.
  refused({"ground.height=0", "initial.mode=landed"}, "rope.length");
  // A landed load whose top stands above the rope's top (about 68 m up): the rope cannot hang
  // down to it, however long.
  refused({"ground.height=70", "initial.mode=landed", "rope.length=66"}, "ground.height");
  refused({"ground.height=0", "payload.height=90", "initial.mode=landed", "rope.length=66"},
          "ground.height");
  refused({"ground.height=0", "rope.model=reduced", "rope.reduction=subdomains"}, "ground");
  refused({"ground.height=0", "rope.tension_only=false", "rope.length=66", "initial.mode=landed"},
          "initial.mode");
  // A hanging or released start whose load would begin inside the ground (60 m of rope from a
  // top about 68 m up, the ground 10 m up): the key named, in every rope model.
  for (const char* model : {"rope.model=full", "rope.model=reduced", "rope.model=pendulum"}) {
    refused({"ground.height=10", model}, "rope.length");
    refused({"ground.height=10", model, "initial.mode=stress_free"}, "rope.length");
  }
  // A ground beyond any site (docs/scenes.md: within a kilometre of the crane's base), hanging
  // or landed: refused before anything is computed from it.
  for (const char* height : {"ground.height=1e300", "ground.height=-1e300", "ground.height=1001"}) {
    refused({height}, "ground.height");
    refused({height, "initial.mode=landed"}, "ground.height");
  }
}

// The landed start's message names the rope's top as the structure holds what hangs from it: a
// load the rope cannot reach (or above the top) must not first weigh the structure down by the
// rope its span would take (a kilometre of it sank the modal T8036's top to z = -28 m).
TEST(GroundLanding, AnUnreachableLandedLoadIsNamedFromTheTopItsRopeHolds) {
  const std::string crane = std::string(CRANE_TWIN_SOURCE_DIR) + "/config/cranes/t8036.yaml";
  const std::string base = "crane: " + crane + R"(
duration: 1.0
time_step: 0.001
rope: {model: full, elements: 10, length: 60.0}
payload: {mass: 3600}
trolley: {radius: 30}
initial: {mode: landed}
)";
  // The message of a refused start, and the top z it names.
  auto refusal = [&](const std::vector<std::string>& sets, double& top_z) {
    const std::string path = writeScene("unreachable", base);
    try {
      const CraneModel m = buildCraneModel(loadScene(path, sets));
      std::unique_ptr<Simulation> sim = makeSimulation(m);
      sim->initialize();
    } catch (const InputError& e) {
      const std::string what = e.what();
      const std::string tag = "rope's top (z = ";
      const std::size_t at = what.find(tag);
      top_z = at == std::string::npos ? std::nan("") : std::stod(what.substr(at + tag.size()));
      return what;
    }
    return std::string("accepted");
  };
  // 900 m down: 60 m of rope do not reach; 900 m up: the load stands above the rope's top.
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"ground.height=-900", "rope.length"}, {"ground.height=900", "ground.height"}};
  for (const auto& [height, key] : cases) {
    double rigid_top = 0.0, modal_top = 0.0;
    const std::string rigid = refusal({height, "structure.model=rigid"}, rigid_top);
    const std::string modal =
        refusal({height, "structure.model=modal", "structure.modes=10"}, modal_top);
    EXPECT_NE(rigid.find("key '" + key + "'"), std::string::npos) << rigid;
    EXPECT_NE(modal.find("key '" + key + "'"), std::string::npos) << modal;
    // The rigid top is the undeformed one (about 68 m up); the modal run's sinks under the
    // trolley and at most the 60 m of rope there are (centimetres), not under the span's rope.
    EXPECT_GT(rigid_top, 60.0) << rigid;
    EXPECT_NEAR(modal_top, rigid_top, 0.5) << modal;
  }
  // Two grounds out of reach: the same 60 m of rope hang from the top either way, so the top
  // the messages name is the same.
  double near_top = 0.0, far_top = 0.0;
  refusal({"ground.height=-100", "structure.model=modal", "structure.modes=10"}, near_top);
  refusal({"ground.height=-1000", "structure.model=modal", "structure.modes=10"}, far_top);
  EXPECT_NEAR(far_top, near_top, 1e-9);
}

// The rope settled between two held points (the landed start's off-centre rope) against the
// elastic catenary (Irvine, Cable Structures, 1981): ends at one height a span S apart, weight w
// per unstretched length L0, horizontal tension H,
//   S = H L0 / EA + (2 H / w) asinh(w L0 / (2 H)),
//   sag f = w L0^2 / (8 EA) + (H / w) (sqrt(1 + (w L0 / (2 H))^2) - 1).
// A nearly flexible rope (EI = 1 N m^2: a bending length sqrt(EI / H) of 2 cm), 50.2 m over a
// 50 m span from a parabola's guess; its sag within 1 mm of the closed form's 2.0 m, and a rope
// already in equilibrium takes no iteration.
TEST(GroundLanding, ARopeBetweenHeldEndsSettlesIntoTheElasticCatenary) {
  const double S = 50.0, L0 = 50.2, mu = 1.9, EA = 2.2e7, g = 9.81, w = mu * g;
  AncfRope rope(40, L0, mu, EA, 1.0, 500.0, Eigen::Vector3d(0.0, 0.0, -g));
  rope.setTensionOnly(true);
  const auto span = [&](double H) {
    return H * L0 / EA + 2.0 * H / w * std::asinh(w * L0 / (2.0 * H));
  };
  double lo = 1.0, hi = 1e6;  // span(H) rises with H
  for (int i = 0; i < 200; ++i) (span(0.5 * (lo + hi)) < S ? lo : hi) = 0.5 * (lo + hi);
  const double H = 0.5 * (lo + hi), b = w * L0 / (2.0 * H);
  const double sag = w * L0 * L0 / (8.0 * EA) + H / w * (std::sqrt(1.0 + b * b) - 1.0);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(rope.dofs());
  for (int j = 0; j < rope.nodes(); ++j) {
    const double x = S * j / rope.elements(), u = 2.0 * x / S - 1.0;
    const Eigen::Vector3d slope(S, 0.0, 2.0 * 1.5 * u * 2.0);  // d/dx of -1.5 (1 - u^2), times S
    q.segment<3>(6 * j) = Eigen::Vector3d(x, 0.0, -1.5 * (1.0 - u * u));
    q.segment<3>(6 * j + 3) = slope.normalized();
  }
  const int iterations = settleBetweenHeldEnds(rope, q);
  const double mid = -rope.position(q, rope.elements() / 2).z();
  std::printf("sag %.5f m (closed form %.5f m, H = %.1f N) after %d Newton iterations\n", mid, sag,
              H, iterations);
  EXPECT_GT(iterations, 0);
  EXPECT_NEAR(mid, sag, 1e-3);
  EXPECT_NEAR(rope.position(q, rope.elements()).x(), S, 1e-12);  // the ends held
  EXPECT_LE(settleBetweenHeldEnds(rope, q), 1);
}

// A landed start begins at rest: the structure deflected under what the rope's top actually
// carries (the whole unloaded rope, the hook block on a rigging, an off-centre rope's sideways
// pull), so nothing rings when it is released; off-centre the rope settled between the trolley
// and the load, and a rigging's hook block where the bars balance it (hung straight and
// inclined, the rope's weight across it sagged it 6.7 mm within 0.2 s, 0.16 m within 1 s, and
// the hook block swung towards plumb, 6.2 mm in the pendulum). The top tension stays within 5 %
// of its start and every node within 1 mm for 0.2 s in every rope model, and every model's start
// carries what full order's does, but for the pendulum off-centre without a rigging: its
// straight bar does not pull the 1.6 kN of the load to the top that the settled rope does.
// (The structure deflected under a vertical guess rang: the pendulum's top tension jumped from
// 1.2 kN to 26 kN, and to 204 kN on a rigging, with a working-load warning; full order's by
// 20 %.)
// 7 t landed at 40 m under 66 m of rope, 0.2 s (the landed starts' tests).
const char* const kLandedAtForty = R"(duration: 0.2
time_step: 0.001
structure: {model: modal, modes: 100}
rope: {elements: 60, length: 66.0}
payload: {mass: 7000}
trolley: {radius: 40}
ground: {height: 1.0}
initial: {mode: landed}
)";

TEST(GroundLanding, ALandedStartBeginsAtRest) {
  const std::string scene = t8036Scene("at_rest", kLandedAtForty);
  for (const char* offset : {"initial.payload_offset=[0, 0]", "initial.payload_offset=[2, 0]"}) {
    const bool under = std::string(offset).find("[0, 0]") != std::string::npos;
    for (const char* rigging : {"hook.rigging_length=0", "hook.rigging_length=4"}) {
      double full_start = NAN;
      for (const char* model : {"rope.model=full", "rope.model=reduced", "rope.model=pendulum"}) {
        SCOPED_TRACE(std::string(model) + " " + rigging + " " + offset);
        const CraneModel cm = buildCraneModel(loadScene(scene, {model, rigging, offset}));
        std::unique_ptr<Simulation> sim = makeSimulation(cm);
        sim->initialize();
        const double start = sim->series().rope_top_tension;
        // The ground carries the load where the start sinks it, m g / k: no more (a rigging's
        // hoist rope stretched by the whole bar's weight sank it 5.8e-5 m deeper, 74.5 kN).
        if (std::string(model) != "rope.model=pendulum") {
          EXPECT_NEAR(sim->series().contact_force, cm.end_mass * cm.scene.gravity,
                      1e-6 * cm.end_mass * cm.scene.gravity);
        }
        if (std::isnan(full_start)) full_start = start;
        std::vector<Eigen::Vector3d> nodes;
        for (int j = 0; j < sim->ropeNodes(); ++j) nodes.push_back(sim->ropeNode(j));
        double worst = 0.0, moved = 0.0;
        while (sim->time() < 0.2 - 1e-9) {
          sim->step();
          worst = std::max(worst, std::abs(sim->series().rope_top_tension - start));
          for (int j = 0; j < sim->ropeNodes(); ++j)
            moved = std::max(moved, (sim->ropeNode(j) - nodes[j]).norm());
        }
        std::printf(
            "%s %s %s: top tension %.1f N at the start, within %.3g %% over 0.2 s; nodes within "
            "%.3g m\n",
            model, rigging, offset, start, 100.0 * worst / start, moved);
        EXPECT_LT(worst, 0.05 * start);
        EXPECT_LT(moved, 1e-3);
        // (Off-centre without a rigging the pendulum's bar is straight, the rope sags: above.)
        if (under || std::string(model) != "rope.model=pendulum" ||
            std::string(rigging) == "hook.rigging_length=4") {
          EXPECT_NEAR(start, full_start, 0.01 * full_start);
        }
      }
    }
  }
}

// A landed start in a steady wind (docs/model.md "Ground contact"): the slack-tensioned rope
// (only its own weight, about 2.5 kN at the top) settles between its held top and hook under its
// weight and the wind on it, so it starts at rest, bowed downwind, and the reduced rope takes
// that start. (Hung straight, the wind blew it sideways from the first step: the reduced run
// began at full order, rang there and never came back; an unseen windy pick ran 1.0x.)
TEST(GroundLanding, ALandedStartInASteadyWindBeginsAtRestBlownDownwind) {
  const std::string scene = t8036Scene("windy_landed", kLandedAtForty);
  const std::vector<std::string> wind = {"structure.modes=20",
                                         "wind={speed: 15, direction_deg: 90}"};
  for (const char* model : {"rope.model=full", "rope.model=reduced"}) {
    SCOPED_TRACE(model);
    std::vector<std::string> sets = wind;
    sets.push_back(model);
    std::unique_ptr<Simulation> sim = makeSimulation(buildCraneModel(loadScene(scene, sets)));
    sim->initialize();
    // Downwind is +y in the world at slewing angle 0 (the air moves towards 90 deg): the rope's
    // middle stands off the chord from its top to its hook by decimetres.
    const int n = sim->ropeNodes();
    const Eigen::Vector3d top = sim->ropeNode(0), hook = sim->ropeNode(n - 1);
    const Eigen::Vector3d mid = sim->ropeNode(n / 2);
    const double off_chord = mid.y() - 0.5 * (top.y() + hook.y());
    std::vector<Eigen::Vector3d> nodes;
    for (int j = 0; j < n; ++j) nodes.push_back(sim->ropeNode(j));
    const double start = sim->series().rope_top_tension;
    double worst = 0.0, moved = 0.0;
    while (sim->time() < 0.2 - 1e-9) {
      sim->step();
      worst = std::max(worst, std::abs(sim->series().rope_top_tension - start));
      for (int j = 0; j < n; ++j) moved = std::max(moved, (sim->ropeNode(j) - nodes[j]).norm());
    }
    std::printf(
        "%s: the middle %.3f m downwind of the chord; top tension %.1f N, within %.3g %% "
        "over 0.2 s; nodes within %.3g m; %ld full-order steps\n",
        model, off_chord, start, 100.0 * worst / start, moved, sim->series().full_order_steps);
    EXPECT_GT(off_chord, 0.1);
    EXPECT_LT(moved, 1e-3);
    EXPECT_LT(worst, 0.05 * start);
    EXPECT_EQ(sim->series().full_order_steps, 0);
  }
}

// An equilibrium start whose unstretched rope hangs the load clear of the ground but whose static
// equilibrium (the rope stretched under the load, the structure deflected) would put it inside
// the ground is refused in every rope model, naming rope.length; a ground a centimetre under the
// stretched equilibrium's underside is accepted and carries nothing at the start. (The pendulum
// started such a load 0.37 m inside the ground and threw it up at 12 m/s; full order rested part
// of its weight on the ground.)
TEST(GroundLanding, AnEquilibriumStartThatStretchesIntoTheGroundIsRefused) {
  const std::string scene = t8036Scene("stretch", R"(duration: 1.0
time_step: 0.001
structure: {model: modal, modes: 20}
rope: {model: full, elements: 20, length: 60.0}
payload: {mass: 7200, height: 2.0}
trolley: {radius: 55}
)");
  // The stretched equilibrium's underside (no ground) and the unstretched rope's.
  std::unique_ptr<Simulation> free = makeSimulation(buildCraneModel(loadScene(scene, {})));
  free->initialize();
  const double stretched = free->series().payload.z() - 2.0;
  const double unstretched = topHeight(scene, {"structure.model=rigid"}) - 60.0 - 2.0;
  ASSERT_LT(stretched, unstretched - 0.05);  // the stretch and the deflection matter here
  char inside[64], clear[64];
  std::snprintf(inside, sizeof inside, "ground.height=%.6f", 0.5 * (stretched + unstretched));
  std::snprintf(clear, sizeof clear, "ground.height=%.6f", stretched - 0.01);
  for (const char* model : {"rope.model=full", "rope.model=reduced", "rope.model=pendulum"}) {
    SCOPED_TRACE(model);
    try {
      std::unique_ptr<Simulation> sim =
          makeSimulation(buildCraneModel(loadScene(scene, {model, inside})));
      sim->initialize();
      ADD_FAILURE() << "accepted a start inside the ground";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("'rope.length'"), std::string::npos) << what;
      EXPECT_NE(what.find("static equilibrium"), std::string::npos) << what;
    }
    std::unique_ptr<Simulation> sim =
        makeSimulation(buildCraneModel(loadScene(scene, {model, clear})));
    sim->initialize();
    EXPECT_EQ(sim->series().contact_force, 0.0);
    EXPECT_NEAR(sim->series().payload.z() - 2.0, stretched, 0.01);
  }
}

namespace {
// Full order and the default reduced rope side by side for `steps` steps: the largest payload
// distance and rope RMS distance (node by node) between the two, every 10 steps, each run's
// lift-off factor (the steps' peak, as crane_sim reports it) and the reduced run's statistics.
struct ReducedAgainstFull {
  double payload = 0.0, rope_rms = 0.0;
  LiftOffMonitor full_lift, reduced_lift;
  RunStatistics stats;
};

ReducedAgainstFull runSideBySide(const CraneModel& full, const CraneModel& reduced, long steps) {
  std::unique_ptr<Simulation> a = makeSimulation(full), b = makeSimulation(reduced);
  a->initialize();
  b->initialize();
  ReducedAgainstFull r;
  StepTensionPeak pa, pb;
  for (long k = 1; k <= steps; ++k) {
    a->step();
    b->step();
    pa.addStep(a->topTension());
    pb.addStep(b->topTension());
    if (k % 10 != 0) continue;
    const SeriesValues va = a->series(), vb = b->series();
    r.full_lift.observe(va, staticTopTension(full, va.rope_length),
                        pa.takeAtRow(va.rope_top_tension));
    r.reduced_lift.observe(vb, staticTopTension(reduced, vb.rope_length),
                           pb.takeAtRow(vb.rope_top_tension));
    r.payload = std::max(r.payload, (va.payload - vb.payload).norm());
    double sum = 0.0;
    for (int j = 0; j < a->ropeNodes(); ++j) sum += (a->ropeNode(j) - b->ropeNode(j)).squaredNorm();
    r.rope_rms = std::max(r.rope_rms, std::sqrt(sum / a->ropeNodes()));
  }
  r.stats = b->statistics();
  return r;
}

// The reduced run's hand-overs and full-order steps and its distance from full order, labelled.
void printAgainstFull(const char* what, const ReducedAgainstFull& r) {
  std::printf(
      "%s: %ld hand-over(s), %ld full-order steps, payload %.3g m and rope RMS %.3g m from full "
      "order\n",
      what, r.stats.hand_overs, r.stats.full_order_steps, r.payload, r.rope_rms);
}

// A shipped scene with `sets`, its default reduced rope against full order.
ReducedAgainstFull runReducedAgainstFull(const std::string& scene_name, long steps,
                                         std::vector<std::string> sets = {}) {
  const std::string scene =
      std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/" + scene_name + ".yaml";
  const CraneModel reduced = buildCraneModel(loadScene(scene, sets));
  sets.push_back("rope.model=full");
  return runSideBySide(buildCraneModel(loadScene(scene, sets)), reduced, steps);
}
}  // namespace

// The default reduced rope carries the ground itself: a landed start and its lift-off stay
// reduced (no step at full order), within 1 cm of full order, with the same dynamic factor; the
// load lumped at the hook and on a rigging.
TEST(GroundLanding, ReducedRopeCarriesALandedStartAndItsLiftOff) {
  const std::string scene = writeScene(
      "reduced_lift", std::string("crane: ") + CRANE_TWIN_SOURCE_DIR + R"(/config/cranes/t8036.yaml
duration: 6.0
time_step: 0.001
output_interval: 0.01
structure: {model: modal, modes: 20}
rope: {model: reduced, elements: 40, length: 66.0}
payload: {mass: 3600}
trolley: {radius: 30}
ground: {height: 0.0}
initial: {mode: landed}
commands:
  - {t: 0.0, hoist_speed: -1.0}
  - {t: 4.0, hoist_speed: 0.0}
)");
  // The load lumped at the hook, and on 4 m of rigging under the hook block.
  for (const char* rigging : {"hook.rigging_length=0", "hook.rigging_length=4"}) {
    SCOPED_TRACE(rigging);
    const CraneModel full = buildCraneModel(loadScene(scene, {"rope.model=full", rigging}));
    const CraneModel reduced = buildCraneModel(loadScene(scene, {rigging}));
    const ReducedAgainstFull r = runSideBySide(full, reduced, 6000);
    std::printf(
        "reduced lift-off: %ld full-order steps, payload %.3g m from full order, phi_2 %.4f "
        "against %.4f\n",
        r.stats.full_order_steps, r.payload, r.reduced_lift.factor(), r.full_lift.factor());
    EXPECT_EQ(r.stats.full_order_steps, 0);
    EXPECT_EQ(r.reduced_lift.liftOffs(), 1);
    EXPECT_LT(r.payload, 0.01);
    EXPECT_NEAR(r.reduced_lift.factor(), r.full_lift.factor(), 0.01 * r.full_lift.factor());
  }
}

// A lift-off that throws its load (4.4 t lifted at 1 m/s on four falls of the rigid T8036 at
// 19 m, phi_2 near 3): the reduced rope's Newton fails in the bouncing, and the step goes to full
// order whole. Halved at reduced order instead (before), its 4 halved steps read a lift-off
// factor of 3.98 against full order's 2.94 (+35 %).
// The factor of one such run is not reproducible to a few per cent: the load's bounces after the
// throw part with round-off, so changes of the payload's mass by 1e-9 to 1e-8 of itself move full
// order's factor between 2.69 and 3.10 and the reduced run's between 2.77 and 3.29 (ten masses
// within 4e-5 kg of 4434 kg; docs/validation.md "Loads on the ground"), while full order's payload
// moves by 1 mm. So the factor is compared as the median over five masses about 1e-9 of each other
// apart, against the halving's bias, and the payload at the scene's own mass.
TEST(GroundLanding, AThrownLiftOffHandsOverAtTheFirstFailedStep) {
  std::vector<double> full_factors, reduced_factors;
  for (double dm : {-9e-6, -4e-6, 0.0, 4e-6, 9e-6}) {
    char mass[64];
    std::snprintf(mass, sizeof mass, "payload.mass=%.6f", 4434.0 + dm);
    SCOPED_TRACE(mass);
    // (the scene's rope is the default reduced one)
    const ReducedAgainstFull r =
        runReducedAgainstFull("t8036_pick_and_place", 5000,
                              {"structure.model=rigid", "rope.falls=4", mass, "trolley.radius=19",
                               "duration=5", "rope.elements=30"});
    std::printf(
        "thrown lift-off (%s): %ld hand-overs, %ld halved steps, phi_2 %.4f against %.4f, "
        "payload %.3g m from full order\n",
        mass, r.stats.hand_overs, r.stats.halved_steps, r.reduced_lift.factor(),
        r.full_lift.factor(), r.payload);
    ASSERT_EQ(r.full_lift.liftOffs(), 1);
    ASSERT_EQ(r.reduced_lift.liftOffs(), 1);
    ASSERT_GT(r.full_lift.factor(), 2.0);  // thrown
    EXPECT_GE(r.stats.hand_overs, 1);
    EXPECT_EQ(r.stats.halved_steps, 0);
    if (dm == 0.0) {
      EXPECT_LT(r.payload, 0.01);
    }
    full_factors.push_back(r.full_lift.factor());
    reduced_factors.push_back(r.reduced_lift.factor());
  }
  const auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  EXPECT_NEAR(median(reduced_factors), median(full_factors), 0.1 * median(full_factors));
}

// t8036_off_centre_lift: the rope, slanted 2 m to the load, drags it before it lifts and leaves
// waves of 0.8 to 3 mm on the swinging rope. Its landed start, the catenary between the trolley
// and the load with a bending layer at the hook, is not in the scene's basis (6.3e-5 m dropped,
// the indicator 1.3 to 1.6 mm on that unloaded rope): the run adds the start's shapes to the basis
// (InvariantReducedSimulation::kStartShapeTolerance) and carries the drag, the lift-off and the
// swing reduced from the first step, within 1 cm of full order. On the scene's basis it began at
// full order and came back after 2.9 s, once the rope hung firmly taut.
TEST(GroundLanding, ReducedRopeCarriesAnOffCentreLiftFromItsLandedStart) {
  const ReducedAgainstFull r = runReducedAgainstFull("t8036_off_centre_lift", 6000);
  printAgainstFull("off-centre lift-off", r);
  EXPECT_EQ(r.stats.hand_overs, 0);
  EXPECT_EQ(r.stats.full_order_steps, 0);
  EXPECT_LT(r.payload, 0.01);
  EXPECT_LT(r.rope_rms, 0.01);
}

// t8036_set_down: the load lands vertically, the jib springs up under the lost load and rings
// (0.28 Hz, 18 cm), and at each of its low points the rope's lowest point nearly unloads. The
// touchdown hands over for a second; the run then stays reduced. The error indicator's static
// correction grows as 1 / N where a point nears zero tension (8.5 mm at 11.72 s with the lowest
// strain at 1.6e-6, 0.1 % of the load's), not with the state's error, and handed this run over
// three more times (4909 full-order steps in 20 s) for no accuracy (the rope within 9.2 mm RMS of
// full order either way): it now waits while a point carries under a tenth of the load's
// weight (InvariantReducedSimulation::kIndicatorStrainFraction).
TEST(GroundLanding, ReducedRopeStaysReducedOnASetDownLoad) {
  const ReducedAgainstFull r = runReducedAgainstFull("t8036_set_down", 16000);
  printAgainstFull("set-down", r);
  EXPECT_EQ(r.stats.hand_overs, 1);  // the touchdown's
  EXPECT_FALSE(r.stats.integrating_full_order);
  EXPECT_LT(r.stats.full_order_steps, 1500);
  // A touchdown is no quiet hand-over: its trials wait the second (docs/model.md "Hand-over to
  // full order": trials from 0.1 s let a pick-and-place on a rigging back into the jib's rebound
  // and 1.04 cm from full order).
  EXPECT_GE(r.stats.full_order_steps, 1000);
  EXPECT_LT(r.payload, 0.01);
  EXPECT_LT(r.rope_rms, 0.01);
}

// The set-down's load rests on the ground from 4.2 s and the run is reduced again from 5.2 s; the
// jib rings above it and the rope's tension, and with it the sticking friction's slope
// mu N / v_s, moves a little every step. The reduced iteration matrix is refactorised where the
// ground's tangent moved by a tenth (kContactTangentChange): at 1e-3 of it these 4000 steps took
// 4172 dense LU factorisations, at a tenth 83, at 2.00 Newton corrections a step either way. Over
// 6 to 10 s: at most one factorisation in 20 steps, and under 3 corrections a step.
TEST(GroundLanding, ARestingLoadsFrictionDoesNotRefactoriseEveryStep) {
  const std::string scene =
      std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/t8036_set_down.yaml";
  const CraneModel model = buildCraneModel(loadScene(scene, {"duration=10"}));
  std::unique_ptr<Simulation> run = makeSimulation(model);
  auto* reduced = dynamic_cast<InvariantReducedSimulation*>(run.get());
  ASSERT_NE(reduced, nullptr);
  run->initialize();
  const long from = 6000, to = 10000;
  for (long k = 1; k <= from; ++k) run->step();
  ASSERT_FALSE(run->statistics().integrating_full_order);
  ASSERT_TRUE(run->series().payload_landed) << "the load rests on the ground";
  const InvariantReducedSolver* solver = &reduced->solver();
  const long factorisations = solver->factorizations(), corrections = solver->newtonIterations();
  for (long k = from + 1; k <= to; ++k) run->step();
  ASSERT_EQ(&reduced->solver(), solver) << "the same solver over the window";
  ASSERT_EQ(run->statistics().hand_overs, 1);
  const long f = solver->factorizations() - factorisations;
  const double per_step =
      static_cast<double>(solver->newtonIterations() - corrections) / (to - from);
  std::printf("resting load, %ld steps: %ld factorisations, %.2f corrections a step\n", to - from,
              f, per_step);
  EXPECT_LE(f, (to - from) / 20);
  EXPECT_LT(per_step, 3.0);
}

// A light load (1.6 t) set down at 44.6 m on the rigid structure: the touchdown hands over, and
// the run comes back once the landed load's rope loses under 0.5 mm to the projection. The
// hand-back's energy bound (1e-4 of the rope's kinetic and strain energy and its swing's) held it
// at full order until 11.06 s (4819 full-order steps in 20 s) for the waves' millijoules on an
// unloaded rope of about 14 J; a resting load has no swing, and the bound is not asked of it.
TEST(GroundLanding, ReducedRopeComesBackOnALightLoadAtRest) {
  const ReducedAgainstFull r =
      runReducedAgainstFull("t8036_set_down", 10000,
                            {"payload.mass=1605", "trolley.radius=44.6", "ground.friction=0.98",
                             "structure.model=rigid"});
  printAgainstFull("light set-down", r);
  EXPECT_EQ(r.stats.hand_overs, 1);
  EXPECT_FALSE(r.stats.integrating_full_order);
  EXPECT_LT(r.stats.full_order_steps, 1500);
  EXPECT_LT(r.payload, 0.01);
  EXPECT_LT(r.rope_rms, 0.01);
}

// A landed load dragged by slewing before any hoisting (4 t at 30 m, the crane slewing at
// 0.03 rad/s for 6 s; 30 elements, 20 modes): the rope slants, pulls up to 60 kN and drags the
// load 2.7 m; when the load stops, the jib springs back and the slanted rope unloads onto the
// resting load, sagging into the catenary with a bending layer at the hook that the basis does
// not hold, where the error indicator is blind (under a tenth of the load's weight). Carried
// reduced until the rope slackened 0.8 s later, the run ended 8.0 mm rope RMS from full order
// at 14 s (1.3 cm at 20 s on 60 elements and 100 modes, where full order at half the step is
// 0.84 mm from itself); handed over as the rope unloads (restingRopeUnloaded), 0.73 mm.
TEST(GroundLanding, ARopeUnloadingOntoADraggedLoadHandsOver) {
  const ReducedAgainstFull r = runReducedAgainstFull(
      "t8036_lift_off_slow", 14000,
      {"duration=14", "payload.mass=4000", "ground.friction=0.4", "rope.elements=30",
       "structure.modes=20", "commands=[{t: 0, slew_rate: 0.03}, {t: 6, slew_rate: 0}]"});
  printAgainstFull("dragged load", r);
  EXPECT_GE(r.stats.hand_overs, 1);
  EXPECT_LT(r.payload, 0.01);
  EXPECT_LT(r.rope_rms, 0.002);
}

// 6.8 t landed 2 m off the trolley's vertical on four falls of the rigid T8036 (30 elements),
// its rope carrying only itself, and the trolley driven 1.2 m towards it at 0.3 m/s: the rope's
// sag grows as its chord shortens, in shapes the basis (the landed start's) does not hold, where
// the error indicator is blind (the rope's end unloaded). Carried reduced, the run was 2.0 cm
// rope RMS from full order when the trolley stopped (4.1 s) and 4.0 cm at 14.2 s, where full
// order at half the step is 5.1 mm from itself; it now hands over once the drives moved the top
// by kDragTolerance (restingRopeDragged).
TEST(GroundLanding, ATrolleyDraggingAnUnloadedRopeOverARestingLoadHandsOver) {
  const ReducedAgainstFull r = runReducedAgainstFull(
      "t8036_off_centre_lift", 6000,
      {"duration=6", "payload.mass=6791", "trolley.radius=12.7", "structure.model=rigid",
       "rope.elements=30", "rope.falls=4", "ground.friction=0.86",
       "commands=[{t: 0, trolley_speed: 0.30}, {t: 4.1, trolley_speed: 0}]"});
  printAgainstFull("dragged unloaded rope", r);
  EXPECT_GE(r.stats.hand_overs, 1);
  EXPECT_LT(r.payload, 0.01);
  EXPECT_LT(r.rope_rms, 0.005);
}

// A 4 t load on a 4 m rigging set down at 0.8 m/s (30 elements, 20 modes): the hoist pays out
// 0.3 m after the touchdown, the rigging goes slack and the hook block (2 t) bobs alone on the
// rope with the jib's rebound. Handed back a second after the touchdown, the reduced rope, shaped
// for the hook and payload lumped, carried that and ended 5.7 mm rope RMS from full order (1.2 cm
// on 60 elements and 100 modes over 15 s, where full order at half the step is 0.7 cm from
// itself); the hand-back now waits while a resting payload's rigging is slack (kSlackRigging).
TEST(GroundLanding, NoHandBackWhileALandedPayloadsRiggingIsSlack) {
  const ReducedAgainstFull r =
      runReducedAgainstFull("t8036_set_down", 10000,
                            {"duration=10", "payload.mass=4000", "hook.rigging_length=4",
                             "rope.length=58.8", "rope.elements=30", "structure.modes=20",
                             "commands=[{t: 0, hoist_speed: 0.8}, {t: 4, hoist_speed: 0}]"});
  printAgainstFull("set-down on a rigging", r);
  EXPECT_EQ(r.stats.hand_overs, 1);  // the touchdown's, and no hand-back after it
  EXPECT_TRUE(r.stats.integrating_full_order);
  EXPECT_LT(r.payload, 0.01);
  EXPECT_LT(r.rope_rms, 0.002);
}

// Scenes nobody ships (seeded draws, the same on every machine): a load of 0.5 to 12.5 t landed
// at 15 m up to the load chart's radius (at most 50 m) on a ground 3 to 10 m up (the drum's 66 m
// reach the lightest load's hook on the ground from there), friction 0 to 1, 10 cm of rope
// lying on it, reeled in at 0.3 to 1 m/s by 1.6 m, held 2 s, lowered by as much onto the
// ground, then 2 s with the hoist at rest. In the full, default
// reduced and pendulum ropes: no numerical failure, one lift, the load on the ground at the end
// within 1 cm of penetration, no energy created once the hoist is at rest (the contact and the
// slack rope only dissipate), and the reduced rope's payload within 1 cm of full order's.
TEST(GroundLanding, UnseenLoadsLiftAndSetDownWithoutFailureOrEnergyCreated) {
  std::mt19937 rng(2026);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const std::string base = std::string("crane: ") + CRANE_TWIN_SOURCE_DIR +
                           "/config/cranes/t8036.yaml\n"
                           "duration: 10.0\ntime_step: 0.001\noutput_interval: 0.01\n"
                           "structure: {model: modal, modes: 20}\n"
                           "rope: {elements: 30, length: 60.0}\n"
                           "initial: {mode: landed}\n";
  for (int draw = 0; draw < 4; ++draw) {
    // Within the load chart (rated moment 410 t m): the radius drawn up to where the mass may go.
    // One draw from each third of the masses: a light, a middle and a heavy load; a fourth of
    // any mass on a rigging of 2 to 6 m under the hook block.
    const bool rigged = draw == 3;
    const double mass = 500.0 + 4000.0 * (rigged ? 3.0 * unit(rng) : draw + unit(rng));
    const double rigging = rigged ? 2.0 + 4.0 * unit(rng) : 0.0;
    const double radius = 15.0 + (std::min(50.0, 410000.0 / mass) - 15.0) * unit(rng);
    const double height = 3.0 + 7.0 * unit(rng), friction = unit(rng), v = 0.3 + 0.7 * unit(rng);
    std::ostringstream text;
    text << base << "payload: {mass: " << mass << "}\ntrolley: {radius: " << radius
         << "}\nground: {height: " << height << ", friction: " << friction
         << "}\nhook: {rigging_length: " << rigging << "}\n";
    const std::string scene = writeScene("unseen_" + std::to_string(draw), text.str());
    // Reel in the 0.1 m lying on the load and 1.5 m more (the rope's stretch and the jib's sag
    // under a rated load take up to about a metre of it before the load leaves the ground);
    // hold; lower 1.6 m; at rest 2 s (the hoist ramps at 0.5 m/s^2: v / 0.5 s to stop).
    const double up = 1.6 / v, stop = v / 0.5;
    const double t_hold = up, t_lower = t_hold + 2.0, t_rest = t_lower + up;
    const double quiet = t_rest + stop + 0.01;
    std::ostringstream cmd;
    cmd << "commands=[{t: 0, hoist_speed: " << -v << "}, {t: " << t_hold
        << ", hoist_speed: 0}, {t: " << t_lower << ", hoist_speed: " << v << "}, {t: " << t_rest
        << ", hoist_speed: 0}]";
    std::vector<Eigen::Vector3d> payload_full;
    for (const std::string model : {"full", "reduced", "pendulum"}) {
      std::vector<std::string> sets = {"rope.model=" + model, cmd.str(),
                                       "duration=" + std::to_string(quiet + 2.0)};
      // The rope's top over the landed load (the drum's 66 m leaves rope lying on it), and the
      // hanging length from there to the hook.
      std::vector<std::string> probe_sets = sets;
      probe_sets.push_back("rope.length=66");
      const CraneModel probe = buildCraneModel(loadScene(scene, probe_sets));
      std::unique_ptr<Simulation> landed = makeSimulation(probe);
      landed->initialize();
      const double top = landed->series().trolley.z();
      const double reach =
          top - (probe.scene.ground->height + probe.scene.payload_height) - rigging;
      sets.push_back("rope.length=" + std::to_string(reach + 0.1));
      const CraneModel m = buildCraneModel(loadScene(scene, sets));
      std::unique_ptr<Simulation> sim = makeSimulation(m);
      sim->initialize();
      LiftOffMonitor monitor;
      const double underside = m.scene.ground->height + m.scene.payload_height;
      double penetration = 0.0, e_quiet = NAN, e_max_after = -1e300, worst = 0.0;
      std::size_t row = 0;
      const long steps = std::lround(m.scene.duration / m.scene.time_step);
      bool failed = false;
      for (long k = 1; k <= steps && !failed; ++k) {
        try {
          sim->step();
        } catch (const std::exception& e) {
          ADD_FAILURE() << model << " draw " << draw << ": " << e.what();
          failed = true;
        }
        if (k % 10 != 0) continue;
        const SeriesValues s = sim->series();
        ASSERT_TRUE(std::isfinite(s.energy) && s.payload.allFinite()) << model << " " << s.t;
        monitor.observe(s, staticTopTension(m, s.rope_length));
        penetration = std::max(penetration, underside - s.payload.z());
        if (s.t <= quiet + 1e-9) e_quiet = s.energy;
        if (s.t >= quiet) e_max_after = std::max(e_max_after, s.energy);
        if (model == "full") payload_full.push_back(s.payload);
        if (model == "reduced" && row < payload_full.size()) {
          worst = std::max(worst, (s.payload - payload_full[row]).norm());
        }
        ++row;
      }
      const SeriesValues end = sim->series();
      std::printf(
          "draw %d (%.0f kg, r %.1f m, ground %.2f m, mu %.2f, v %.2f m/s, rigging %.2f m) %s: "
          "lifts %d, phi_2 %.3f, penetration %.2e m, energy rise at rest %.2e J, landed %d, "
          "payload %.2e m from full order, full-order steps %ld\n",
          draw, mass, radius, height, friction, v, rigging, model.c_str(), monitor.liftOffs(),
          monitor.factor(), penetration, e_max_after - e_quiet, end.payload_landed ? 1 : 0, worst,
          sim->statistics().full_order_steps);
      EXPECT_EQ(monitor.liftOffs(), 1) << model << " draw " << draw;
      EXPECT_TRUE(end.payload_landed) << model << " draw " << draw;
      EXPECT_LT(penetration, 0.01) << model << " draw " << draw;
      EXPECT_LE(e_max_after, e_quiet + 1e-9 * std::abs(e_quiet) + 1e-6)
          << model << " draw " << draw;
      if (model == "reduced") {
        EXPECT_LT(worst, 0.01) << "draw " << draw;
      }
    }
  }
}

// A step halved while the crane slews (RopeSupport::setStepFraction). The shipped slow lift-off
// under random commands on all three drives: the pendulum's load, swung by the slewing, lands
// sliding at 8.0 s, where Newton fails at the full step (the contact's damper switching on) and
// the step is halved. Each half step held the rope at the full step's end pose, so the first had
// to follow the trolley's whole 1 ms of motion (0.3 mm) in half the time: its constraint force
// took that as an impulse, the trolley point's velocity then alternated by 2 m/s from step to
// step and the top tension read 7.3 MN for 0.1 s (full order: 62 kN at most). Held at each half
// step's own pose, the pendulum's peak top tension stays within 25 % of full order's over the
// same 8.3 s.
TEST(GroundLanding, AStepHalvedWhileTheCraneSlewsHoldsTheRopeAtEachHalfsPose) {
  const std::string scene =
      std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/t8036_lift_off_slow.yaml";
  const std::vector<std::string> sets = {
      "duration=8.3", "commands=null",
      "random_commands={seed: 5, interval: 4.0, slew: true, trolley: true, hoist: true}"};
  double peak[2] = {0.0, 0.0};
  long halved = 0;
  for (int k = 0; k < 2; ++k) {
    std::vector<std::string> s = sets;
    s.push_back(k == 0 ? "rope.model=pendulum" : "rope.model=full");
    std::unique_ptr<Simulation> sim = makeSimulation(buildCraneModel(loadScene(scene, s)));
    sim->initialize();
    while (sim->time() < 8.3 - 1e-9) {
      sim->step();
      peak[k] = std::max(peak[k], sim->series().rope_top_tension);
    }
    if (k == 0) halved = sim->statistics().halved_steps;
  }
  std::printf("peak top tension: pendulum %.0f N, full %.0f N; pendulum halved steps %ld\n",
              peak[0], peak[1], halved);
  EXPECT_GT(halved, 0);  // (the case this test is about)
  EXPECT_LT(peak[0], 1.25 * peak[1]);
  EXPECT_GT(peak[0], 0.75 * peak[1]);
}
