// Cost of one ANCF cable element force + tangent evaluation and of one beam element.
#include <benchmark/benchmark.h>

#include "crane_twin/elements/ancf_cable_element.hpp"
#include "crane_twin/elements/timoshenko_beam_element.hpp"

using namespace crane_twin;

static void BM_AncfForceAndTangent(benchmark::State& state) {
  AncfCableProperties p;
  p.length = 0.5;
  p.mass_per_length = 3.8;
  p.axial_stiffness = 4.4e7;
  p.bending_stiffness = state.range(0) ? 157.0 : 0.0;
  Vector12 e;
  e << 0, 0, 0, 0.01, 0.02, -1.001, 0.004, 0.011, -0.5004, -0.01, 0.03, -0.9995;
  Vector12 Q;
  Matrix12 K;
  for (auto _ : state) {
    ancfElasticForce(p, e, Q, &K);
    benchmark::DoNotOptimize(K.data());
  }
}
BENCHMARK(BM_AncfForceAndTangent)->Arg(1)->Arg(0)->ArgName("bending");

static void BM_AncfForceOnly(benchmark::State& state) {
  AncfCableProperties p;
  p.length = 0.5;
  p.mass_per_length = 3.8;
  p.axial_stiffness = 4.4e7;
  p.bending_stiffness = 157.0;
  Vector12 e;
  e << 0, 0, 0, 0.01, 0.02, -1.001, 0.004, 0.011, -0.5004, -0.01, 0.03, -0.9995;
  Vector12 Q;
  for (auto _ : state) {
    ancfElasticForce(p, e, Q);
    benchmark::DoNotOptimize(Q.data());
  }
}
BENCHMARK(BM_AncfForceOnly);

static void BM_TimoshenkoBeamGlobal(benchmark::State& state) {
  const BeamSection s = BeamSection::circularTube(0.2, 0.01, 2.06e11, 7.9e10, 7850);
  for (auto _ : state) {
    auto m = timoshenkoBeamGlobal(s, {0, 0, 0}, {1.0, 0.5, 2.0}, {0, 0, 1});
    benchmark::DoNotOptimize(m.K.data());
  }
}
BENCHMARK(BM_TimoshenkoBeamGlobal);
