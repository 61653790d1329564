// Cost of building the T8036 structure and of its lowest modes (ARPACK shift-invert + CHOLMOD),
// solved for or read from the mode cache.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>

#include "crane_twin/io/scene.hpp"
#include "crane_twin/simulation/crane_model.hpp"
#include "crane_twin/structure/modal_analysis.hpp"
#include "crane_twin/structure/modal_cache.hpp"
#include "crane_twin/structure/tower_crane_structure.hpp"

using namespace crane_twin;

namespace {
const std::string kCrane = std::string(CRANE_TWIN_SOURCE_DIR) + "/config/cranes/t8036.yaml";
}

static void BM_T8036Build(benchmark::State& state) {
  const CraneDescription c = loadCraneDescription(kCrane);
  for (auto _ : state) {
    auto s = TowerCraneStructure::build(c);
    benchmark::DoNotOptimize(s.K.nonZeros());
  }
}
BENCHMARK(BM_T8036Build)->Unit(benchmark::kMillisecond);

static void BM_T8036Modes(benchmark::State& state) {
  const TowerCraneStructure s = TowerCraneStructure::build(loadCraneDescription(kCrane));
  ModalOptions opt;
  opt.count = static_cast<int>(state.range(0));
  for (auto _ : state) {
    auto b = lowestModes(s.K, s.M, opt);
    benchmark::DoNotOptimize(b.omega2.data());
  }
}
BENCHMARK(BM_T8036Modes)->Arg(10)->Arg(100)->ArgName("modes")->Unit(benchmark::kMillisecond);

// The same modes read from the mode cache (docs/architecture.md "Mode cache"): the key's hashes
// of K and M, the file's read and its content hash, against BM_T8036Modes' solve.
static void BM_T8036ModesCached(benchmark::State& state) {
  const TowerCraneStructure s = TowerCraneStructure::build(loadCraneDescription(kCrane));
  ModalOptions opt;
  opt.count = static_cast<int>(state.range(0));
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("crane_twin_bench_modes_" + std::to_string(::getpid()));
  cachedLowestModes(s.K, s.M, opt, dir.string());  // (written once)
  for (auto _ : state) {
    auto b = cachedLowestModes(s.K, s.M, opt, dir.string());
    benchmark::DoNotOptimize(b.omega2.data());
  }
  std::filesystem::remove_all(dir);
}
BENCHMARK(BM_T8036ModesCached)->Arg(100)->ArgName("modes")->Unit(benchmark::kMillisecond);

// What a copy of the T8036 structure costs (its K, M and geometry): what each simulation and
// forecaster paid when it copied the model with the structure inside, against a copy of the
// model now (the structure and the modes shared, docs/architecture.md).
static void BM_T8036StructureCopy(benchmark::State& state) {
  const TowerCraneStructure s = TowerCraneStructure::build(loadCraneDescription(kCrane));
  for (auto _ : state) {
    TowerCraneStructure copy = s;
    benchmark::DoNotOptimize(copy.K.nonZeros());
  }
}
BENCHMARK(BM_T8036StructureCopy)->Unit(benchmark::kMicrosecond);

static void BM_T8036ModelCopy(benchmark::State& state) {
  const CraneModel m = buildCraneModel(
      loadScene(std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/t8036_live.yaml", {}));
  for (auto _ : state) {
    CraneModel copy = m;
    benchmark::DoNotOptimize(copy.end_mass);
  }
}
BENCHMARK(BM_T8036ModelCopy)->Unit(benchmark::kMicrosecond);
