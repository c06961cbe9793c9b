// Sample kernels: packing generation, bond detection, own-format writing and reading, statistics,
// on the reduced tissue (a few thousand particles). `rupture sample generate --preset tissue`
// measures the full-size generator (docs/sample.md).
#include <benchmark/benchmark.h>

#include "sample/formats.hpp"
#include "sample/generator.hpp"
#include "sample/presets.hpp"
#include "sample/stats.hpp"

namespace {

const rupture::Sample& tissue_small() {
  static const rupture::Sample sample = rupture::make_preset("tissue-small", 1);
  return sample;
}

void generate_tissue_small(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(rupture::make_preset("tissue-small", 1));
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(tissue_small().size()));
}
BENCHMARK(generate_tissue_small)->Unit(benchmark::kMillisecond);

void make_bonds(benchmark::State& state) {
  rupture::Sample sample = tissue_small();
  const double tolerance = rupture::preset_params("tissue-small").bond_tolerance;
  for (auto _ : state) {
    rupture::make_bonds(sample, tolerance);
    benchmark::DoNotOptimize(sample.bonds.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(sample.size()));
}
BENCHMARK(make_bonds)->Unit(benchmark::kMillisecond);

void own_format_write_and_read(benchmark::State& state) {
  for (auto _ : state)
    benchmark::DoNotOptimize(rupture::parse_own(rupture::format_own(tissue_small()), "bench"));
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(tissue_small().size()));
}
BENCHMARK(own_format_write_and_read)->Unit(benchmark::kMillisecond);

void sample_stats(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(rupture::compute_stats(tissue_small()));
}
BENCHMARK(sample_stats)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
