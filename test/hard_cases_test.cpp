// The hard cases of docs/stability.md, each a shipped scene: run (shortened, coarser where the
// full scene is long) and checked for a finite state, a bounded constraint error, energy that
// never grows where nothing feeds it, and the end time reached. docs/stability.md reports the
// full-length runs (scripts/hard_cases.sh).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "crane_twin/simulation/crane_simulation.hpp"
#include "crane_twin/simulation/subdomain_reduced_simulation.hpp"

using namespace crane_twin;

namespace {

struct Case {
  const char* scene;
  std::vector<std::string> sets;          ///< to keep the test short
  bool energy_fed;                        ///< drives work on the system: no energy bound
  double peak_min = 0.0, peak_max = 0.0;  ///< > 0: bounds on max tension / hanging weight
};

struct Outcome {
  double duration = 0.0, t_end = 0.0, max_constraint = 0.0, e0 = 0.0, e_max = 0.0, weight = 0.0,
         max_tension = 0.0;
  bool finite = true;
};

Outcome run(const Case& c) {
  const std::string path = std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/" + c.scene;
  const CraneModel model = buildCraneModel(loadScene(path, c.sets));
  std::unique_ptr<Simulation> sim = makeSimulation(model);
  sim->initialize();
  Outcome o;
  o.duration = model.scene.duration;
  SeriesValues v = sim->series();
  o.e0 = o.e_max = v.energy;
  o.max_tension = v.rope_top_tension;
  o.weight = (model.end_mass + model.ropeMass()) * model.scene.gravity;
  const long steps = std::lround(model.scene.duration / model.scene.time_step);
  for (long k = 1; k <= steps; ++k) {
    sim->step();
    if (k % 10 != 0 && k != steps) continue;
    v = sim->series();
    o.finite = o.finite && v.payload.allFinite() && v.payload_velocity.allFinite() &&
               std::isfinite(v.energy) && std::isfinite(v.rope_top_tension) && v.cab.allFinite() &&
               v.jib_tip.allFinite();
    o.max_constraint = std::max(o.max_constraint, v.constraint_error);
    o.e_max = std::max(o.e_max, v.energy);
    o.max_tension = std::max(o.max_tension, v.rope_top_tension);
  }
  o.t_end = sim->time();
  return o;
}

void check(const Case& c) {
  SCOPED_TRACE(c.scene);
  const Outcome o = run(c);
  EXPECT_TRUE(o.finite);
  EXPECT_NEAR(o.t_end, o.duration, 1e-6 * o.duration);
  EXPECT_LT(o.max_constraint, 1e-9);
  if (!c.energy_fed) {
    // Physical and numerical damping only take energy out: allow round-off on the total
    // (gravity potential included, ~1e6 J) and nothing more.
    EXPECT_LE(o.e_max - o.e0, 1e-9 * std::abs(o.e0) + 1e-3)
        << "energy grew by " << o.e_max - o.e0 << " J";
  }
  if (c.peak_min > 0.0) {
    EXPECT_GE(o.max_tension, c.peak_min * o.weight);
    EXPECT_LE(o.max_tension, c.peak_max * o.weight);
  }
}

}  // namespace

TEST(HardCases, LargeSwing30Deg) {
  check({"hard_swing_30deg.yaml", {"duration=3", "rope.elements=40"}, false});
}

TEST(HardCases, LargeSwing60Deg) {
  check({"hard_swing_60deg.yaml", {"duration=3", "rope.elements=40"}, false});
}

TEST(HardCases, LargeSwing30DegReduced) {
  check({"hard_swing_30deg.yaml",
         {"duration=3", "rope.elements=40", "rope.model=reduced", "rope.mode_count=10"},
         false});
}

TEST(HardCases, LargeSwing60DegReducedHandsTheSlackRopeToFullOrder) {
  // Released at 60 deg the rope goes almost slack after 0.19 s; the reduced model integrates
  // that episode at full order (SubdomainReducedSimulation) instead of blowing up (35 MN before).
  check({"hard_swing_60deg.yaml",
         {"duration=1", "rope.elements=40", "rope.model=reduced", "rope.mode_count=10"},
         false});
  const std::string path =
      std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/hard_swing_60deg.yaml";
  SubdomainReducedSimulation sim(buildCraneModel(
      loadScene(path, {"rope.elements=40", "rope.model=reduced", "rope.mode_count=10"})));
  sim.initialize();
  double max_tension = 0.0;
  for (int k = 0; k < 1000; ++k) {
    sim.step();
    max_tension = std::max(max_tension, sim.series().rope_top_tension);
  }
  EXPECT_GE(sim.slackEpisodes(), 1);
  EXPECT_GT(sim.fullOrderSteps(), 50);
  EXPECT_FALSE(sim.integratingFullOrder() && sim.fullOrderSteps() == 1000);  // it came back
  // The full model's largest tension in this second is the released state's (1.135e5 N).
  EXPECT_LT(max_tension, 1.3e5);
}

TEST(HardCases, LargeSwing60DegReducedStaysBelowTheBreakingForce) {
  // The whole 20 s on 40 elements; the full model's largest top tension is 179 kN. Handing the
  // rope back as soon as it was taut, the reduced run chattered between the models every other
  // step and peaked at 1.24 MN, over the 690 kN breaking force. The hand-back now waits until
  // the new basis carries the state's kinetic energy, which at this swing it never does: the
  // run stays at full order after the first slack episode (a reduced model that cannot
  // represent the motion says so and steps aside).
  const std::string path =
      std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/hard_swing_60deg.yaml";
  const CraneModel model = buildCraneModel(
      loadScene(path, {"rope.elements=40", "rope.model=reduced", "rope.mode_count=10"}));
  SubdomainReducedSimulation sim(model);
  sim.initialize();
  double max_tension = 0.0;
  for (int k = 0; k < 20000; ++k) {
    sim.step();
    max_tension = std::max(max_tension, sim.series().rope_top_tension);
  }
  std::printf(
      "60 deg, 40 elements, reduced: max top tension %.0f N, %d slack episodes, %ld "
      "refused hand-backs, %ld full-order steps\n",
      max_tension, sim.slackEpisodes(), sim.refusedHandBacks(), sim.fullOrderSteps());
  EXPECT_GT(sim.refusedHandBacks(), 0);
  EXPECT_LT(max_tension, 0.5 * model.rope.breaking_force);
}

TEST(HardCases, SwingOnA2mRope) { check({"hard_short_rope_2m.yaml", {"duration=5"}, false}); }

TEST(HardCases, SlackRopeSnapsTaut) {
  // Thrown up at 3 m/s the load rises ~0.46 m and falls back onto the rope: the snap at least
  // doubles the static tension; the step halving has to carry the run through.
  check({"hard_slack_throw.yaml", {"duration=1.5", "rope.elements=40"}, false, 2.0, 10.0});
}

TEST(HardCases, StressFreeReleaseBouncesToTwiceTheStaticTension) {
  // Released unstretched, the load falls onto the rope: a suddenly applied load, whose peak is
  // twice the static tension (closed form for a light spring and a rigid support; the rope's
  // own 228 kg of 14.8 t bends it a little). On the soft T8036 the structure shares the
  // stretch and the peak is lower: bounded, not checked against 2.
  check({"hard_stress_free_heavy.yaml",
         {"duration=1.0", "rope.elements=40", "structure.model=rigid"},
         false,
         1.9,
         2.1});
  check({"hard_stress_free_heavy.yaml", {"duration=1.0", "rope.elements=40"}, false, 1.2, 2.1});
}

TEST(HardCases, EmergencyStopOfSlewing) {
  check({"hard_emergency_stop_slew.yaml",
         {"duration=6", "rope.elements=30",
          "commands=[{t: 0, slew_rate: 0.084}, {t: 4.2, slew_rate: 0}]"},
         true});
}

TEST(HardCases, EmergencyStopOfTheTrolley) {
  check({"hard_emergency_stop_trolley.yaml",
         {"duration=5", "rope.elements=30",
          "commands=[{t: 0, trolley_speed: -1}, {t: 3, trolley_speed: 0}]"},
         true});
}

TEST(HardCases, HoistingTo3mAndBack) {
  // The full 60 -> 3 -> 60 m profile on a coarse rope and step, at full and reduced order.
  check({"hard_hoist_60_3_60.yaml", {"rope.elements=20", "time_step=0.01"}, true});
  check({"hard_hoist_60_3_60.yaml",
         {"rope.elements=20", "time_step=0.01", "rope.model=reduced", "rope.mode_count=10"},
         true});
}

TEST(HardCases, ReducedHoistingTo3mAndBackFollowsFullOrder) {
  // The reduced rope hoists by the full model's rescaling with a static-correction vector and
  // hands steps that change the length fast against the rope's static stretch (here below
  // about 32 m at 10 mm per step) to full order. Before that hand-over, lowering from 3 m
  // failed numerically at 62.6 s on this mesh and step.
  const std::string path =
      std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/hard_hoist_60_3_60.yaml";
  auto with = [&](std::vector<std::string> sets) {
    sets.insert(sets.end(), {"rope.elements=20", "time_step=0.01", "rope.mode_count=10"});
    return buildCraneModel(loadScene(path, sets));
  };
  CraneSimulation full(with({"rope.model=full"}));
  SubdomainReducedSimulation red(with({"rope.model=reduced"}));
  full.initialize();
  red.initialize();
  double err = 0.0;
  for (int k = 0; k < 13000; ++k) {
    full.step();
    red.step();
    err = std::max(err, (full.series().payload - red.series().payload).norm());
  }
  std::printf(
      "60 -> 3 -> 60 m, reduced vs full: payload error %.3g m, %ld fast-hoist hand-overs, "
      "%d slack episodes\n",
      err, red.fastHoistEpisodes(), red.slackEpisodes());
  EXPECT_NEAR(red.crane().ropeLength(), 60.0, 1e-9);
  EXPECT_LT(err, 0.3);  // budget
  // Sentinel: measured 0.0104 m with 2 hand-overs (build/core/hard_cases_test
  // --gtest_filter='*ReducedHoisting*').
  EXPECT_LT(err, 0.04);
  EXPECT_GT(red.fastHoistEpisodes(), 0);
}

TEST(HardCases, UndampedRunDoesNotGainEnergy) {
  check({"hard_one_hour_undamped.yaml", {"duration=60", "rope.elements=20"}, false});
}

TEST(HardCases, LargeTimeStep) {
  check({"hard_large_step.yaml", {"duration=10", "rope.elements=40"}, false});
}

TEST(HardCases, RandomCommandsAreReproducible) {
  const std::string path =
      std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/hard_random_commands.yaml";
  const Scene a = loadScene(path), b = loadScene(path);
  ASSERT_EQ(a.commands.size(), 20u);  // every 3 s over 60 s
  for (size_t i = 0; i < a.commands.size(); ++i) {
    EXPECT_EQ(a.commands[i].slew_rate, b.commands[i].slew_rate);
    EXPECT_LE(std::abs(a.commands[i].slew_rate), a.crane->slewing.max_speed);
    EXPECT_LE(std::abs(a.commands[i].trolley_speed), a.crane->trolley.max_speed);
    EXPECT_EQ(a.commands[i].hoist_speed, 0.0);
  }
  const Scene c = loadScene(path, {"random_commands.seed=1"});
  EXPECT_NE(c.commands[0].slew_rate, a.commands[0].slew_rate);
  check({"hard_random_commands.yaml", {"duration=12", "rope.elements=30"}, true});
  check({"hard_random_commands.yaml",
         {"duration=12", "rope.elements=30", "rope.model=reduced", "rope.mode_count=10"},
         true});
}

TEST(HardCases, RandomCommandsFromALandedLoad) {
  // Lifted off, set down swinging and dragged at random (docs/stability.md): the pendulum at full
  // length (its touchdown at 8.0 s halves a step while the crane slews, which read 125 times the
  // hanging weight before each half step held the rope at its own time's pose), full order and
  // the reduced rope over the first 12 s on a coarser mesh. The peak top tension lies between
  // the hanging weight (the load is lifted) and 5 times it.
  check({"hard_random_landed.yaml", {"rope.model=pendulum"}, true, 1.0, 5.0});
  check({"hard_random_landed.yaml", {"duration=12", "rope.elements=30"}, true, 1.0, 5.0});
  check({"hard_random_landed.yaml",
         {"duration=12", "rope.elements=30", "rope.model=reduced"},
         true,
         1.0,
         5.0});
}

TEST(HardCases, FallingRopeWithoutPayload) {
  check({"hard_falling_rope.yaml", {"duration=2", "rope.elements=30"}, false});
}

TEST(HardCases, PendulumRopeThroughTheHardCases) {
  // The cheapest rung (rope.model: pendulum) on every case where a straight bar makes sense
  // (not the falling rope, whose point is its large deformation), at the full scenes' length
  // where that is cheap: the hour-long undamped run included.
  const std::string p = "rope.model=pendulum";
  check({"hard_swing_60deg.yaml", {p}, false});
  check({"hard_short_rope_2m.yaml", {p}, false});
  check({"hard_slack_throw.yaml", {p}, false, 2.0, 10.0});
  check({"hard_stress_free_heavy.yaml", {p, "structure.model=rigid"}, false, 1.9, 2.1});
  check({"hard_emergency_stop_slew.yaml", {p}, true});
  check({"hard_emergency_stop_trolley.yaml", {p}, true});
  check({"hard_hoist_60_3_60.yaml", {p}, true});
  check({"hard_one_hour_undamped.yaml", {p}, false});
  check({"hard_large_step.yaml", {p}, false});
  check({"hard_random_commands.yaml", {p}, true});
}
