// cli/bench_command: `rupture bench`, whole DEM steps timed on a named sample (intact and with a
// fraction of its bonds broken) for each thread count: particle-steps per second, the split over
// the step's stages, bytes per particle and the state hash (equal for every thread count).
// `rupture bench --run CONFIG` times a whole run instead, end to end (outputs, separation checks,
// rebuild storms after failure included), in a temporary folder removed afterwards.
#include <fmt/format.h>
#include <omp.h>
#include <unistd.h>

#include <chrono>
#include <ctime>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "core/error.hpp"
#include "core/hash.hpp"
#include "core/random.hpp"
#include "dem/system.hpp"
#include "io/atomic_file.hpp"
#include "io/quantity.hpp"
#include "loading/config.hpp"
#include "loading/ramp.hpp"
#include "loading/run.hpp"
#include "rupture/version.hpp"
#include "sample/formats.hpp"
#include "sample/presets.hpp"

namespace rupture::cli {

namespace {

struct BenchOptions {
  std::string sample = "tissue";
  std::vector<int> threads{1, 2};
  std::vector<double> broken{0.0, 0.5};
  long steps = 1000;
  std::uint64_t seed = 1;
  bool json = false;
  std::string run;  // a run config to time end to end instead
  std::vector<std::string> overrides;
};

struct BenchResult {
  int threads = 0;
  double broken_fraction = 0.0;
  std::size_t particles = 0, bonds = 0, broken = 0;
  long steps = 0;
  double wall_s = 0.0;
  double cpu_s = 0.0;  // process CPU time (all threads): on a shared machine wall time also counts waiting
  dem::StageTimes stages;
  std::size_t rebuilds = 0, memory_bytes = 0;
  std::uint64_t hash = 0;
  double rate() const { return double(particles) * double(steps) / wall_s; }
};

double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

Sample bench_sample(const BenchOptions& options) {
  if (std::filesystem::exists(options.sample)) return load_sample(options.sample);
  return make_preset(options.sample, options.seed);
}

// Steps the sample as a run would (default physics, automatic dt, plate at 50 mm/s) with bonds
// broken beforehand in a seeded random selection, so every thread count sees the same state.
BenchResult bench_case(const Sample& sample, const BenchOptions& options, int threads,
                       double broken_fraction) {
  omp_set_num_threads(threads);
  dem::System system(sample, dem::Params{});
  for (std::size_t b = 0; b < system.bond_count(); ++b)
    if (Rng(options.seed, RandomStream::dem_bond_order, b).uniform01() < broken_fraction)
      system.break_bond(b);
  system.break_events().clear();
  const double dt = 0.4 * system.critical_dt();
  const loading::SpeedRamp plate{50.0, 0.0};
  long step = 0;
  for (; step < 20; ++step) system.step(dt, plate.at(double(step + 1) * dt));  // warm caches and lists
  const dem::StageTimes before = system.stage_times();
  const std::size_t rebuilds_before = system.neighbour_rebuilds();
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = process_cpu_seconds();
  for (long s = 0; s < options.steps; ++s, ++step) system.step(dt, plate.at(double(step + 1) * dt));
  BenchResult r;
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.cpu_s = process_cpu_seconds() - cpu_start;
  r.threads = threads;
  r.broken_fraction = broken_fraction;
  r.particles = system.size();
  r.bonds = system.bond_count();
  r.broken = system.bond_count() - system.intact_bonds();
  r.steps = options.steps;
  const dem::StageTimes& after = system.stage_times();
  r.stages = {after.neighbours - before.neighbours, after.integrate - before.integrate,
              after.forces - before.forces, after.plates - before.plates, after.breaks - before.breaks};
  r.rebuilds = system.neighbour_rebuilds() - rebuilds_before;
  r.memory_bytes = system.memory_bytes();
  r.hash = system.state_hash();
  return r;
}

nlohmann::json to_json(const BenchResult& r, const std::string& sample) {
  return {{"sample", sample},
          {"particles", r.particles},
          {"bonds", r.bonds},
          {"broken_bonds", r.broken},
          {"steps", r.steps},
          {"threads", r.threads},
          {"wall_time", io::quantity(r.wall_s, "s")},
          {"cpu_time", io::quantity(r.cpu_s, "s")},
          {"throughput", io::quantity(r.rate(), "particle-steps/s")},
          {"stage_times", loading::to_json(r.stages)},
          {"neighbour_rebuilds", r.rebuilds},
          {"memory_per_particle", io::quantity(double(r.memory_bytes) / double(r.particles), "B")},
          {"state_hash", fmt::format("{:016x}", r.hash)}};
}

// A whole run of `config_file` on `threads` threads in a temporary folder: what run.json reports
// (steps, wall time, stages, rebuilds) and a hash of curves.csv and breaks.csv without their comment
// lines, equal for every thread count.
nlohmann::json bench_run(const BenchOptions& options, int threads) {
  loading::RunConfig config = loading::load_config(options.run, options.overrides);
  config.threads = threads;
  const Sample sample = loading::resolve_sample(config);
  const auto folder =
      std::filesystem::temp_directory_path() / fmt::format("rupture-bench-run-{}-{}", ::getpid(), threads);
  std::filesystem::remove_all(folder);
  // The temporary folder goes however the run ends (a failed run throws).
  struct RemoveAtExit {
    std::filesystem::path folder;
    ~RemoveAtExit() {
      std::error_code ignored;
      std::filesystem::remove_all(folder, ignored);
    }
  } remove_at_exit{folder};
  loading::RunOptions run_options;
  run_options.echo_warnings = false;
  const double cpu_start = process_cpu_seconds();
  const loading::RunSummary summary =
      loading::run_simulation(config, sample, folder, "rupture bench --run " + options.run, run_options);
  const double cpu_s = process_cpu_seconds() - cpu_start;
  const auto report = nlohmann::json::parse(io::read_file(folder / "run.json"));
  Fnv1a outputs;
  for (const char* name : {"curves.csv", "breaks.csv"}) {
    const std::string text = io::read_file(folder / name);
    std::size_t line = 0;
    while (line < text.size()) {
      const std::size_t end = std::min(text.find('\n', line), text.size());
      if (text[line] != '#') outputs.add(text.data() + line, end - line);
      line = end + 1;
    }
  }
  return {{"config", options.run},
          {"particles", sample.size()},
          {"bonds", sample.bonds.size()},
          {"threads", threads},
          {"steps", summary.steps},
          {"stop_reason", summary.stop_reason},
          {"broken_bonds", summary.broken_bonds},
          {"wall_time", report["wall_time"]},
          {"cpu_time", io::quantity(cpu_s, "s")},
          {"throughput", report["throughput"]},
          {"stage_times", report["stage_times"]},
          {"neighbour_rebuilds", report["neighbour_rebuilds"]},
          {"outputs_hash", fmt::format("{:016x}", outputs.hash)}};
}

void print_run_benches(const BenchOptions& options) {
  nlohmann::json results = nlohmann::json::array();
  if (!options.json)
    fmt::print("rupture {} bench --run {}\n{:>7} {:>9} {:>9} {:>8} {:>12} {:>7} {:>7} {:>7} {:>8} {:>16}\n",
               version_string, options.run, "threads", "steps", "wall[s]", "cpu[s]", "p-steps/s", "forces",
               "integr", "neighb", "rebuilds", "outputs hash");
  for (const int threads : options.threads) {
    const nlohmann::json r = bench_run(options, threads);
    results.push_back(r);
    if (options.json) continue;
    const auto value = [](const nlohmann::json& q) { return io::quantity_value(q).value_or(NAN); };
    const double wall = value(r["wall_time"]);
    const auto& stages = r["stage_times"];
    fmt::print("{:>7} {:>9} {:>9.3f} {:>8.3f} {:>12.4g} {:>6.0f}% {:>6.0f}% {:>6.0f}% {:>8} {:>16}\n",
               threads, r["steps"].get<std::uint64_t>(), wall, value(r["cpu_time"]), value(r["throughput"]),
               100 * value(stages["forces"]) / wall, 100 * value(stages["integrate"]) / wall,
               100 * value(stages["neighbours"]) / wall, r["neighbour_rebuilds"].get<std::uint64_t>(),
               r["outputs_hash"].get<std::string>());
  }
  if (options.json)
    fmt::print(
        "{}\n",
        nlohmann::json{{"tool", "rupture bench --run"}, {"version", version_string}, {"results", results}}
            .dump(2));
}

}  // namespace

void add_bench_command(CLI::App& app, int&) {
  auto options = std::make_shared<BenchOptions>();
  auto* bench =
      app.add_subcommand("bench", "Time whole DEM steps: particle-steps per second per thread count");
  bench->add_option("--sample", options->sample, "preset name (tissue, tissue-small) or sample file")
      ->capture_default_str();
  bench->add_option("--threads", options->threads, "thread counts to time (repeatable)")
      ->capture_default_str();
  bench->add_option("--broken", options->broken, "fractions of bonds broken beforehand (repeatable)")
      ->capture_default_str();
  bench->add_option("--steps", options->steps, "timed steps per case")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  bench->add_option("--seed", options->seed, "preset seed and broken-bond selection")->capture_default_str();
  bench->add_flag("--json", options->json, "print JSON instead of a table");
  bench->add_option("--run", options->run,
                    "time this run config end to end instead (outputs in a temporary folder, removed)");
  bench->add_option("--set", options->overrides, "with --run: override a config key (repeatable)");
  bench->callback([options] {
    for (int t : options->threads)
      if (t < 1) throw InputError("--threads", fmt::format("{} is not a thread count", t), "use 1 or more");
    for (double f : options->broken)
      if (!(f >= 0.0 && f < 1.0))
        throw InputError("--broken", fmt::format("{} is not a fraction in [0, 1)", f), "use e.g. 0.5");
    if (!options->run.empty()) return print_run_benches(*options);
    if (!options->overrides.empty())
      throw InputError("--set", "overrides a run config's keys, and only --run names one",
                       "add --run CONFIG, or drop --set");
    const Sample sample = bench_sample(*options);
    nlohmann::json results = nlohmann::json::array();
    if (!options->json)
      fmt::print(
          "rupture {} bench: sample {} ({} particles, {} bonds), {} steps per case\n"
          "{:>8} {:>7} {:>9} {:>8} {:>12} {:>10} {:>7} {:>7} {:>7} {:>8} {:>16}\n",
          version_string, options->sample, sample.size(), sample.bonds.size(), options->steps, "broken",
          "threads", "wall[s]", "cpu[s]", "p-steps/s", "ns/p-step", "forces", "integr", "neighb", "rebuilds",
          "state hash");
    for (double fraction : options->broken)
      for (int threads : options->threads) {
        const BenchResult r = bench_case(sample, *options, threads, fraction);
        results.push_back(to_json(r, options->sample));
        if (!options->json)
          fmt::print(
              "{:>8} {:>7} {:>9.3f} {:>8.3f} {:>12.4g} {:>10.2f} {:>6.0f}% {:>6.0f}% {:>6.0f}% {:>8} "
              "{:>16x}\n",
              r.broken, threads, r.wall_s, r.cpu_s, r.rate(), 1e9 / r.rate(),
              100 * r.stages.forces / r.wall_s, 100 * r.stages.integrate / r.wall_s,
              100 * r.stages.neighbours / r.wall_s, r.rebuilds, r.hash);
      }
    if (options->json)
      fmt::print(
          "{}\n",
          nlohmann::json{{"tool", "rupture bench"}, {"version", version_string}, {"results", results}}.dump(
              2));
    else
      fmt::print("bytes per particle (engine arrays, bonds included): {:.0f}\n",
                 io::quantity_value(results.back()["memory_per_particle"]).value_or(NAN));
  });
}

}  // namespace rupture::cli
