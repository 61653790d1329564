// Cost of one full-order (F-ANCF) generalized-alpha step against rope elements, for the rope on
// a fixed anchor and on the T8036 structure (100 modes); the counter `newton` is the mean number
// of Newton iterations per step, so the cost of one iteration is time / newton.
#include <benchmark/benchmark.h>

#include "crane_twin/crane_simulation.hpp"

using namespace crane_twin;

namespace {
const std::string kScenes = std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/";

void runSteps(benchmark::State& state, const std::string& scene, std::vector<std::string> sets) {
  sets.push_back("rope.elements=" + std::to_string(state.range(0)));
  const CraneModel m = buildCraneModel(loadScene(kScenes + scene, sets));
  CraneSimulation sim(m);
  sim.initialize();
  long iterations = 0, steps = 0;
  for (auto _ : state) {
    sim.step();
    iterations += sim.state().newton_iterations;
    ++steps;
  }
  state.counters["newton"] = static_cast<double>(iterations) / steps;
}
}  // namespace

static void BM_FullOrderStepAnchoredRope(benchmark::State& state) {
  runSteps(state, "rope_pendulum_chrono.yaml", {"initial.mode=equilibrium"});
}
BENCHMARK(BM_FullOrderStepAnchoredRope)->Arg(60)->Arg(120)->Arg(240)->Arg(480)->ArgName("elements")
    ->Unit(benchmark::kMicrosecond);

static void BM_FullOrderStepT8036Modal(benchmark::State& state) {
  runSteps(state, "t8036_combination1.yaml", {"rope.model=full"});
}
BENCHMARK(BM_FullOrderStepT8036Modal)->Arg(60)->Arg(120)->Arg(240)->Arg(480)->ArgName("elements")
    ->Unit(benchmark::kMicrosecond);
