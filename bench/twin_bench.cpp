// The twin's costs (docs/twin.md): a 30 s forecast of the live scene (its default 20 ms step,
// and the twin's own 5 ms), one estimator update with its correction, and a load change in a
// running twin (withPayloadMass, continueWithModel, a forecaster for the new load).
#include <benchmark/benchmark.h>

#include "crane_twin/io/scene.hpp"
#include "crane_twin/simulation/crane_model.hpp"
#include "crane_twin/twin/payload_forecast.hpp"
#include "crane_twin/twin/sway_correction.hpp"
#include "crane_twin/twin/sway_estimator.hpp"

using namespace crane_twin;

namespace {
CraneModel liveScene() {
  return buildCraneModel(
      loadScene(std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/t8036_live.yaml", {}));
}
}  // namespace

// Forecast 30 s ahead while slewing and moving the trolley; arg: forecast step [ms].
static void BM_Forecast30s(benchmark::State& state) {
  const CraneModel m = liveScene();
  std::unique_ptr<Simulation> twin = makeSimulation(m);
  twin->initialize();
  for (int k = 0; k < 400; ++k) twin->step();
  PayloadForecaster f(m, 1e-3 * static_cast<double>(state.range(0)));
  CommandEntry c;
  c.slew_rate = 0.03;
  c.trolley_speed = -0.3;
  for (auto _ : state) {
    PayloadForecast p = f.run(*twin, c, 30.0, 0.5);
    benchmark::DoNotOptimize(p);
  }
}
BENCHMARK(BM_Forecast30s)->Arg(20)->Arg(5)->ArgName("step_ms")->Unit(benchmark::kMillisecond);

// The load cell found another load: the model changed, the running simulation continued with
// it, a forecaster built for it (docs/twin.md "Picks and set-downs").
static void BM_TwinLoadChange(benchmark::State& state) {
  const CraneModel m = liveScene();
  std::unique_ptr<Simulation> twin = makeSimulation(m);
  twin->initialize();
  for (int k = 0; k < 100; ++k) twin->step();
  for (auto _ : state) {
    const CraneModel heavier = withPayloadMass(m, m.scene.payload_mass + 1000.0);
    std::unique_ptr<Simulation> next = continueWithModel(heavier, *twin);
    PayloadForecaster f(heavier, 0.01);
    benchmark::DoNotOptimize(next);
    benchmark::DoNotOptimize(f);
  }
}
BENCHMARK(BM_TwinLoadChange)->Unit(benchmark::kMillisecond);

// One payload measurement: the filter's update (with the structure's sideways modes) and the
// correction of the reduced state.
static void BM_EstimatorUpdateAndCorrection(benchmark::State& state) {
  const CraneModel m = liveScene();
  std::unique_ptr<Simulation> twin = makeSimulation(m);
  twin->initialize();
  const std::vector<int> modes = swayCouplingModes(*twin);
  SwayEstimator e(SwayEstimatorSettings{}, modeMotionNorms(*twin, modes));
  for (auto _ : state) {
    e.predict(0.2);
    const SeriesValues row = twin->series();
    const SwayUpdate u = e.update(row.payload.head<2>() + Eigen::Vector2d(0.01, 0.0),
                                  row.payload.head<2>(), swayModelAt(*twin, row, modes, 9.81));
    applyTwinCorrection(*twin, u, modes);
  }
}
BENCHMARK(BM_EstimatorUpdateAndCorrection)->Unit(benchmark::kMicrosecond);
