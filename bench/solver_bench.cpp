// Cost of one full-order (F-ANCF) generalized-alpha step against rope elements, for the rope on
// a fixed anchor and on the T8036 structure (100 modes); the counter `newton` is the mean number
// of Newton iterations per step, so the cost of one iteration is time / newton.
#include <benchmark/benchmark.h>

#include "crane_twin/rope/rope_modes.hpp"
#include "crane_twin/simulation/crane_simulation.hpp"
#include "crane_twin/simulation/invariant_reduced_simulation.hpp"
#include "crane_twin/simulation/subdomain_reduced_simulation.hpp"

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
BENCHMARK(BM_FullOrderStepAnchoredRope)
    ->Arg(60)
    ->Arg(120)
    ->Arg(240)
    ->Arg(480)
    ->ArgName("elements")
    ->Unit(benchmark::kMicrosecond);

static void BM_FullOrderStepT8036Modal(benchmark::State& state) {
  runSteps(state, "t8036_combination1.yaml", {"rope.model=full"});
}
BENCHMARK(BM_FullOrderStepT8036Modal)
    ->Arg(60)
    ->Arg(120)
    ->Arg(240)
    ->Arg(480)
    ->ArgName("elements")
    ->Unit(benchmark::kMicrosecond);

// ---- Reduced order ----------------------------------------------------------------

namespace {
struct RopeTangents {
  SparseMatrix K0, K1, M;
};

// Tangents of the 120-element T8036 rope at its 2.3 deg equilibrium and 0.1 s into the swing.
RopeTangents ropeTangents() {
  const CraneModel m = buildCraneModel(
      loadScene(kScenes + "t8036_combination1.yaml", {"rope.model=full", "structure.modes=20"}));
  CraneSimulation sim(m);
  sim.initialize();
  RopeTangents r;
  r.K0 = sim.rope().tangentStiffness(sim.state().q);
  for (int k = 0; k < 100; ++k) sim.step();
  r.K1 = sim.rope().tangentStiffness(sim.state().q);
  r.M = sim.rope().massMatrix();
  return r;
}
}  // namespace

static void BM_RopeModeUpdate(benchmark::State& state) {
  static const RopeTangents t = ropeTangents();
  RopeModeSettings s;
  s.kept = static_cast<int>(state.range(0));
  const bool warm = state.range(1) != 0;
  const RopeModes start = coldRopeModes(t.K0, t.M, s);
  for (auto _ : state) {
    RopeModes m = warm ? warmRopeModes(t.K1, t.M, start, s) : coldRopeModes(t.K1, t.M, s);
    benchmark::DoNotOptimize(m.phi.data());
  }
}
BENCHMARK(BM_RopeModeUpdate)
    ->Args({10, 1})
    ->Args({10, 0})
    ->Args({20, 1})
    ->Args({20, 0})
    ->Args({360, 1})
    ->Args({360, 0})
    ->ArgNames({"modes", "warm"})
    ->Unit(benchmark::kMillisecond);

static void BM_ReducedStepT8036(benchmark::State& state) {
  // Steps only inside one subdomain (delta large), so the cost is the step's own; frame 1 is the
  // chord's frame (its explicit frame loads, and the displacement check every r / 40 steps).
  const CraneModel m = buildCraneModel(loadScene(
      kScenes + "t8036_combination1.yaml",
      {"rope.model=reduced", "rope.mode_count=" + std::to_string(state.range(0)),
       "rope.subdomain_delta=1000",
       std::string("rope.subdomain_frame=") + (state.range(1) ? "corotational" : "fixed")}));
  SubdomainReducedSimulation sim(m);
  sim.initialize();
  for (auto _ : state) sim.step();
}
BENCHMARK(BM_ReducedStepT8036)
    ->Args({10, 0})
    ->Args({10, 1})
    ->Args({360, 0})
    ->Args({360, 1})
    ->ArgNames({"modes", "corotational"})
    ->Unit(benchmark::kMicrosecond);

// ---- Reduced order on the rotation-invariant basis (the default) --------------------------

static void BM_InvariantReducedForce(benchmark::State& state) {
  // The reduced elastic force alone (one per Newton iteration), at the 2.3 deg equilibrium.
  const CraneModel m = buildCraneModel(
      loadScene(kScenes + "t8036_combination1.yaml",
                {"rope.model=reduced", "rope.elements=" + std::to_string(state.range(0))}));
  InvariantReducedSimulation sim(m);
  sim.initialize();
  const CoupledState& s = sim.reducedState();
  for (auto _ : state) {
    Eigen::VectorXd Q = sim.solver().force(s.q, s.v);
    benchmark::DoNotOptimize(Q.data());
  }
  state.counters["shapes"] = sim.basis().shapes();
}
BENCHMARK(BM_InvariantReducedForce)
    ->Arg(60)
    ->Arg(120)
    ->Arg(240)
    ->ArgName("elements")
    ->Unit(benchmark::kMicrosecond);

static void BM_InvariantReducedStepT8036(benchmark::State& state) {
  // Steps of a 30 deg swing on the T8036 (100 structure modes): the run's own step, with the
  // error indicator every InvariantReducedSimulation::kCheckSteps steps; `newton` as above.
  const CraneModel m = buildCraneModel(
      loadScene(kScenes + "hard_swing_30deg.yaml",
                {"rope.model=reduced", "rope.elements=" + std::to_string(state.range(0))}));
  InvariantReducedSimulation sim(m);
  sim.initialize();
  for (auto _ : state) sim.step();
  state.counters["newton"] =
      static_cast<double>(sim.solver().newtonIterations()) / std::max(1L, sim.solver().steps());
}
BENCHMARK(BM_InvariantReducedStepT8036)
    ->Arg(60)
    ->Arg(120)
    ->Arg(240)
    ->ArgName("elements")
    ->Unit(benchmark::kMicrosecond);
