// The usage count's cost per output row (docs/fatigue.md "Cost"): the lift-off monitor and the
// usage counter (four hot spots rainflow counted as the rows come) fed the rows of 20 s of the
// pick-and-place cycle, against what crane_sim run spends per row integrating them.
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
