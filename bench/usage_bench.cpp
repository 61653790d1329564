// The usage count's cost per output row and per step (docs/fatigue.md "Cost"): the lift-off
// monitor and the usage counter (four hot spots rainflow counted as they come) fed the rows, or
// the steps' stresses, of 20 s of the pick-and-place cycle.
#include <benchmark/benchmark.h>

#include <vector>

#include "crane_twin/analysis/usage_counter.hpp"
#include "crane_twin/io/scene.hpp"
#include "crane_twin/simulation/crane_model.hpp"

using namespace crane_twin;

static void BM_UsageCountRow(benchmark::State& state) {
  const CraneModel m = buildCraneModel(loadScene(
      std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/t8036_pick_and_place.yaml", {}));
  std::unique_ptr<Simulation> sim = makeSimulation(m);
  sim->initialize();
  std::vector<SeriesValues> rows;
  const int every = static_cast<int>(m.scene.output_interval / m.scene.time_step + 0.5);
  for (int k = 0; k < 20000; ++k) {
    sim->step();
    if ((k + 1) % every == 0) rows.push_back(sim->series());
  }
  for (auto _ : state) {
    UsageCounter usage(m);
    LiftOffMonitor lift_off;
    for (const SeriesValues& r : rows) {
      lift_off.observe(r, staticTopTension(m, r.rope_length));
      usage.observe(r, lift_off);
    }
    UsageReport report = usage.report();
    benchmark::DoNotOptimize(report);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(rows.size()));
}
BENCHMARK(BM_UsageCountRow)->Unit(benchmark::kMicrosecond);

// The usage count's share of every step (docs/fatigue.md "Cost"): the hot spots' stresses of the
// step's state (Simulation::hotSpotStresses) fed to the rainflow count, over the 20000 steps of
// the first 20 s of the pick-and-place cycle (the reduced rope; the states stepped once, before).
static void BM_UsageCountStep(benchmark::State& state) {
  const CraneModel m = buildCraneModel(loadScene(
      std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/t8036_pick_and_place.yaml", {}));
  std::unique_ptr<Simulation> sim = makeSimulation(m);
  sim->initialize();
  std::vector<Eigen::VectorXd> stresses;
  for (int k = 0; k < 20000; ++k) {
    sim->step();
    stresses.push_back(sim->hotSpotStresses());
  }
  for (auto _ : state) {
    UsageCounter usage(m);
    for (int k = 0; k < 20000; ++k) {
      benchmark::DoNotOptimize(sim->hotSpotStresses());  // the stresses' own cost
      usage.observeStep(stresses[k]);
    }
    UsageReport report = usage.report();
    benchmark::DoNotOptimize(report);
  }
  state.SetItemsProcessed(state.iterations() * 20000);
}
BENCHMARK(BM_UsageCountStep)->Unit(benchmark::kMicrosecond);
