// Kernels of the loading-curve analysis: the zero-phase Butterworth filter, the Savitzky–Golay
// derivative, and the whole pipeline on a noisy power-law curve of 10^4..10^6 samples.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "analysis/analysis.hpp"
#include "core/random.hpp"

namespace {

rupture::analysis::Curve noisy_curve(std::size_t n) {
  rupture::analysis::Curve c;
  c.source = "bench";
  c.strain_unit = c.force_unit = c.energy_unit = "1";
  rupture::Rng rng(1, rupture::RandomStream::analysis_noise);
  for (std::size_t i = 0; i < n; ++i) {
    const double x = static_cast<double>(i) / static_cast<double>(n - 1);
    const double survive = 1.0 - x * x * x;
    c.strain.push_back(x);
    c.force.push_back(x * survive + 0.002 * rng.normal());
    c.energy.push_back(0.5 * x * x * survive + 1e-5 * rng.normal());
  }
  return c;
}

void BM_sosfiltfilt(benchmark::State& state) {
  const auto c = noisy_curve(static_cast<std::size_t>(state.range(0)));
  const auto sections = rupture::analysis::butterworth_lowpass(4, 0.01);
  for (auto _ : state) benchmark::DoNotOptimize(rupture::analysis::sosfiltfilt(sections, c.force));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_sosfiltfilt)->Arg(10000)->Arg(1000000);

void BM_savgol_derivative(benchmark::State& state) {
  const auto c = noisy_curve(1000000);
  const int window = static_cast<int>(state.range(0));
  for (auto _ : state)
    benchmark::DoNotOptimize(rupture::analysis::savgol_filter(c.energy, window, 3, 1, 1e-6));
  state.SetItemsProcessed(state.iterations() * 1000000);
}
BENCHMARK(BM_savgol_derivative)->Arg(7)->Arg(101);

void BM_analyze_curve(benchmark::State& state) {
  const auto c = noisy_curve(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(rupture::analysis::analyze_curve(c, {}));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_analyze_curve)->Arg(10000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond);

}  // namespace
BENCHMARK_MAIN();
