// What the rotation-invariant basis must hold to carry a snatching rope, and what it costs: the
// Project Chrono rope problem (config/scenes/rope_pendulum_chrono.yaml: 60 m, 120 elements,
// 3.6 t, released stress-free at 2.3 deg, 1 ms) integrated by the reduced rope alone, without a
// hand-over (a run hands this start to full order, docs/model.md "Hand-over to full order"),
// against full order over the same steps. Per basis size (transverse modes): the wall time, and
// as counters the speed-up over full order (measured once, in the same process), the payload's
// largest distance and the rope's largest RMS nodal distance from full order (every 50 steps),
// the energy-consistent and halved steps and the energy's largest rise above its start [J].
// docs/accuracy-vs-time.md "Slack and snatch". By hand, never as a test:
//   build/core/crane_twin_bench --benchmark_filter=StressFreeRelease
// (CRANE_TWIN_RELEASE_SECONDS shortens the 20 s.)
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdlib>
#include <vector>

#include "crane_twin/rope/invariant_rope_basis.hpp"
#include "crane_twin/simulation/crane_simulation.hpp"
#include "crane_twin/solvers/full_order_solver.hpp"
#include "crane_twin/solvers/invariant_reduced_solver.hpp"

using namespace crane_twin;

namespace {

const std::string kScene =
    std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/rope_pendulum_chrono.yaml";
constexpr int kSampleSteps = 50;

double releaseSeconds() {
  const char* s = std::getenv("CRANE_TWIN_RELEASE_SECONDS");
  return s ? std::atof(s) : 20.0;
}

struct Release {
  std::vector<std::vector<Eigen::Vector3d>> nodes;  ///< every kSampleSteps steps
  double seconds = 0.0;                             ///< wall time of the steps
};

// Full order's path, once per process.
const Release& fullRelease(const CraneModel& m) {
  static Release r;
  if (!r.nodes.empty()) return r;
  CraneSimulation crane(m);
  const AncfRope& rope = crane.rope();
  FixedAnchor anchor(m.scene.anchor);
  FullOrderSolver solver(rope, anchor, integratorFor(m.scene), m.scene.time_step);
  CoupledState s = crane.initialState();
  solver.initializeAccelerations(s);
  const long steps = std::lround(releaseSeconds() / m.scene.time_step);
  const auto t0 = std::chrono::steady_clock::now();
  for (long k = 1; k <= steps; ++k) {
    solver.step(s);
    if (k % kSampleSteps == 0) {
      std::vector<Eigen::Vector3d> n;
      for (int j = 0; j < rope.nodes(); ++j) n.push_back(rope.position(s.q, j));
      r.nodes.push_back(n);
    }
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace

static void BM_StressFreeReleaseReducedAlone(benchmark::State& state) {
  const CraneModel m = buildCraneModel(loadScene(kScene, {"rope.model=full"}));
  const Release& full = fullRelease(m);
  CraneSimulation crane(m);
  const AncfRope& rope = crane.rope();
  FixedAnchor anchor(m.scene.anchor);
  InvariantBasisSettings settings;
  settings.transverse_modes = static_cast<int>(state.range(0));
  const InvariantRopeBasis basis(rope, settings);
  const long steps = std::lround(releaseSeconds() / m.scene.time_step);
  double payload = 0.0, rms = 0.0, rise = 0.0, seconds = 0.0;
  long energy_consistent = 0, halved = 0;
  for (auto _ : state) {
    InvariantReducedSolver solver(rope, basis, anchor, integratorFor(m.scene), m.scene.time_step);
    CoupledState s = solver.project(crane.initialState());
    solver.initializeAccelerations(s);
    const double e0 = solver.energy(s);
    payload = rms = rise = 0.0;
    const auto t0 = std::chrono::steady_clock::now();
    for (long k = 1; k <= steps; ++k) {
      solver.step(s);
      rise = std::max(rise, solver.energy(s) - e0);
      if (k % kSampleSteps != 0) continue;
      const std::vector<Eigen::Vector3d>& f = full.nodes[k / kSampleSteps - 1];
      double sum = 0.0;
      for (int j = 0; j < rope.nodes(); ++j)
        sum += (solver.nodePosition(s.q, j) - f[j]).squaredNorm();
      rms = std::max(rms, std::sqrt(sum / rope.nodes()));
      payload = std::max(payload, (solver.nodePosition(s.q, rope.nodes() - 1) - f.back()).norm());
    }
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    energy_consistent = solver.energyConsistentSteps();
    halved = solver.halvedSteps();
  }
  state.counters["coordinates"] = basis.coordinates();
  state.counters["speedup"] = full.seconds / seconds;
  state.counters["payload_m"] = payload;
  state.counters["rope_rms_m"] = rms;
  state.counters["ec_steps"] = energy_consistent;
  state.counters["halved"] = halved;
  state.counters["rise_J"] = rise;
}
BENCHMARK(BM_StressFreeReleaseReducedAlone)
    ->Arg(6)
    ->Arg(12)
    ->Arg(24)
    ->Arg(36)
    ->ArgName("modes")
    ->Iterations(1)
    ->Unit(benchmark::kSecond);
