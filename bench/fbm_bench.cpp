// FBM kernels: drawing thresholds, the exact strain-controlled curve (sort + one pass),
// load-controlled ELS with bursts, LLS on a ring, and the numerical ELS theory. Not a test.
#include <benchmark/benchmark.h>

#include "fbm/bundle.hpp"
#include "fbm/distribution.hpp"
#include "fbm/els_theory.hpp"

namespace {

using namespace rupture::fbm;

void BM_DrawThresholds(benchmark::State& state) {
  const Weibull d(2.0, 1.0);
  for (auto _ : state)
    benchmark::DoNotOptimize(draw_thresholds(d, static_cast<std::size_t>(state.range(0)), 1));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_DrawThresholds)->Arg(1000000)->Arg(10000000)->Unit(benchmark::kMillisecond);

void BM_StrainControlled(benchmark::State& state) {
  const auto thresholds = draw_thresholds(Uniform(0.0, 1.0), static_cast<std::size_t>(state.range(0)), 1);
  for (auto _ : state) benchmark::DoNotOptimize(strain_controlled(thresholds, 2001));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_StrainControlled)->Arg(1000000)->Arg(10000000)->Unit(benchmark::kMillisecond);

void BM_LoadControlledEls(benchmark::State& state) {
  const auto thresholds = draw_thresholds(Uniform(0.0, 1.0), static_cast<std::size_t>(state.range(0)), 1);
  for (auto _ : state) benchmark::DoNotOptimize(load_controlled_els(thresholds, 2001));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_LoadControlledEls)->Arg(1000000)->Arg(10000000)->Unit(benchmark::kMillisecond);

void BM_LoadControlledLls(benchmark::State& state) {
  const auto thresholds = draw_thresholds(Uniform(0.0, 1.0), static_cast<std::size_t>(state.range(0)), 1);
  for (auto _ : state) benchmark::DoNotOptimize(load_controlled_lls(thresholds, 2001));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_LoadControlledLls)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond);

void BM_ElsTheory(benchmark::State& state) {
  const Weibull d(2.0, 1.0);
  for (auto _ : state) benchmark::DoNotOptimize(ElsTheory(d).characteristics());
}
BENCHMARK(BM_ElsTheory)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
