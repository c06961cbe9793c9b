// DEM kernels timed alone (Google Benchmark): a whole step on the reduced and the standard tissue,
// intact and half broken; the energy reduction a curve row costs; the separation check.
// Whole-run throughput for users is `rupture bench` (docs/performance.md).
#include <benchmark/benchmark.h>

#include <map>
#include <string>

#include "core/random.hpp"
#include "dem/system.hpp"
#include "loading/ramp.hpp"
#include "loading/separation.hpp"
#include "sample/presets.hpp"

namespace {

using namespace rupture;

const Sample& preset(const std::string& name) {
  static std::map<std::string, Sample> cache;
  auto it = cache.find(name);
  if (it == cache.end()) it = cache.emplace(name, make_preset(name, 1)).first;
  return it->second;
}

dem::System make_system(const std::string& name, double broken_fraction) {
  dem::System system(preset(name), dem::Params{});
  for (std::size_t b = 0; b < system.bond_count(); ++b)
    if (Rng(1, RandomStream::dem_bond_order, b).uniform01() < broken_fraction) system.break_bond(b);
  return system;
}

// state.range(0): percent of bonds broken beforehand.
void step(benchmark::State& state, const std::string& name) {
  dem::System system = make_system(name, double(state.range(0)) / 100.0);
  const double dt = 0.4 * system.critical_dt();
  const loading::SpeedRamp plate{50.0, 0.0};
  long n = 0;
  for (auto _ : state) {
    ++n;
    system.step(dt, plate.at(double(n) * dt));
  }
  state.counters["particle_steps_per_s"] =
      benchmark::Counter(double(n) * double(system.size()), benchmark::Counter::kIsRate);
}

void BM_StepTissueSmall(benchmark::State& state) { step(state, "tissue-small"); }
void BM_StepTissue(benchmark::State& state) { step(state, "tissue"); }
BENCHMARK(BM_StepTissueSmall)->Arg(0)->Arg(50)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_StepTissue)->Arg(0)->Arg(50)->Unit(benchmark::kMicrosecond);

void BM_Energies(benchmark::State& state) {
  const dem::System system = make_system("tissue", 0.0);
  for (auto _ : state) benchmark::DoNotOptimize(system.energies());
}
BENCHMARK(BM_Energies)->Unit(benchmark::kMicrosecond);

void BM_SeparationCheck(benchmark::State& state) {
  const dem::System system = make_system("tissue", double(state.range(0)) / 100.0);
  loading::UnionFind sets;
  for (auto _ : state) benchmark::DoNotOptimize(loading::separated(system, sets));
}
BENCHMARK(BM_SeparationCheck)->Arg(0)->Arg(50)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
