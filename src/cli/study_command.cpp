// cli/study_command: `rupture study` — the whole study in one command, as `scripts/study` runs it:
// a reduced tissue is generated, pulled to separation, analysed for the precursor; then a small scan
// of the same tissue over (k_n, b_d) gives the paper's figures 15-17 from real runs; one report shows
// the run's loading curves beside delta_x against x_c of the scan. The default configs are embedded
// below and written into the study folder, so the study records exactly what it ran; `--config`,
// `--scan-config` and `--set` change them.
#include <fmt/format.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli/analyze_command.hpp"
#include "cli/commands.hpp"
#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/file_lock.hpp"
#include "loading/config.hpp"
#include "loading/run.hpp"
#include "report/report.hpp"
#include "sample/formats.hpp"
#include "sample/stats.hpp"
#include "scan/farm.hpp"
#include "scan/scan.hpp"

namespace rupture::cli {

namespace {

// The reduced tissue (same material as the paper's 80 x 25 x 5 mm sample, 20 x 10 x 5 mm) pulled at
// the paper's 50 mm/s with a stiffness and breaking distance that give one well-pronounced force
// peak within a few minutes on two cores.
constexpr const char* default_study_config =
    R"(# rupture study: the default reduced tissue pulled to separation.
# Every key: rupture run --help-config. Units: mm, N/mm, g/mm^3, s, mm/s.

[sample]
preset = "tissue-small"       # 20 x 10 x 5 mm, radii 0.2-0.6 mm, ~2,700 particles
seed = 1
density = 2.5e-4              # g/mm^3, as in the paper

[bonds]
stiffness = 1e3               # N/mm
break_distance = 0.005        # mm, absolute rule: a bond breaks when stretched by more than this

[loading]
speed = 50.0                  # mm/s, the paper's plate speed
ramp_steps = 10000            # steps of the smooth start

[stop]
extra_strain = 0.3            # % pulled on after the sample has separated
max_strain = 1.5              # %: the default tissue fails near 0.4 %

[output]
interval = 200                # steps between curve rows
snapshot_interval = 10000     # steps between bond snapshots (about ten over the run; the report draws three)

[run]
threads = 2
)";

// The scan of the study: nine cheap points of the same tissue (about 40 s on two cores, 10 s per
// point at most), k_n and b_d each over a decade so that x_c spans 0.25-1.6 %, with the rules of the
// study scans in docs/study/ (the ramp, row interval and stop strain scaled to each point's first-
// break strain). `base` is the study's run config; `--set` overrides reach every point as well.
constexpr const char* default_scan_config =
    R"(# rupture study: the small scan of the study's tissue (figures 15-17 from real runs).
# Every key: docs/scan.md. Run again by hand from the study folder: rupture scan scan.toml

[scan]
base = "study.toml"
output = "scan"
set = ["stop.max_strain=200", "output.snapshot_interval=0"]   # the scaled stop strain rules; no snapshots

[grid]                                          # log-spaced, both ends included
k_n = { from = 10, to = 100, count = 3 }        # N/mm
b_d = { from = 0.003, to = 0.02, count = 3 }    # mm

[rules]
dt = "auto"                  # time.safety x the critical dt of each point
ramp = "strain"              # the speed ramp ends at ramp_fraction of the first-break strain
ramp_fraction = 0.1
ramp_min_steps = 500
interval = "scaled"          # a curve row so that 400 rows lie below the first-break strain
rows_to_first_break = 400
max_strain = "scaled"        # stop at 3 x the first-break strain (>= 1 %)
max_strain_factor = 3
max_strain_min = 1.0
)";

struct StudyOptions {
  std::string out = "study";
  std::string config;
  std::string scan_config;
  bool no_scan = false;
  std::vector<std::string> overrides;
};

std::string command_line(const StudyOptions& o) {
  std::string command = "rupture study --out " + o.out;
  if (!o.config.empty()) command += " --config " + o.config;
  if (!o.scan_config.empty()) command += " --scan-config " + o.scan_config;
  if (o.no_scan) command += " --no-scan";
  for (const auto& s : o.overrides) command += " --set " + s;
  return command;
}

// The scan of the study, planned (every point's config checked) before anything runs; with --no-scan
// none, and an earlier study's scan is removed so that it cannot enter this report.
std::optional<scan::Plan> plan_scan(const StudyOptions& o, const std::filesystem::path& out,
                                    const Sample& sample) {
  if (o.no_scan) {
    std::filesystem::remove_all(out / "scan");
    std::filesystem::remove(out / "scan.toml");
    return std::nullopt;
  }
  const std::filesystem::path scan_file =
      o.scan_config.empty() ? out / "scan.toml" : std::filesystem::path(o.scan_config);
  if (o.scan_config.empty()) io::write_file_atomically(scan_file, default_scan_config);
  scan::ScanConfig config = scan::load_scan_config(scan_file);
  config.output = out / "scan";
  config.set.insert(config.set.end(), o.overrides.begin(), o.overrides.end());  // --set reaches every point
  return scan::make_plan(config, sample);
}

// The last line: where the report is and what the run's precursor was.
void print_outcome(const std::string& html, const analysis::AnalysisResult& r) {
  if (r.x_p && r.x_c && r.delay) {
    fmt::print(
        "report: {}; precursor: x_p = {:.3g} %, x_c = {:.3g} % (delta_x = {:.2g} +- {:.1g} %, 95 % "
        "[{:.2g}, {:.2g}] %{}): {}{}\n",
        html, r.x_p->value, r.x_c->value, r.delay->mean, r.delay->sd, r.delay->ci95_low, r.delay->ci95_high,
        analysis::calibration_mark(r.interval_scales.calibrated),
        analysis::precursor_order(r.delay->ci95_low, r.delay->ci95_high),
        r.accepted ? "" : "; analysis rejected: " + r.rejection);
  } else {
    fmt::print("report: {}; no precursor found ({})\n", html, r.accepted ? "no peak" : r.rejection);
  }
}

}  // namespace

void add_study_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<StudyOptions>();
  auto* cmd = app.add_subcommand(
      "study",
      "The whole study on the default reduced tissue: generate, pull to separation, analyse, plot, report");
  cmd->add_option("-o,--out", o->out, "Study folder (created; its run/ folder is replaced)");
  cmd->add_option("--config", o->config, "Run config to use instead of the embedded default (TOML)");
  cmd->add_option("--scan-config", o->scan_config,
                  "Scan config to use instead of the embedded 9-point scan (TOML; its base is read from its "
                  "own folder)");
  cmd->add_flag("--no-scan", o->no_scan, "Only the single run: no scan, no figures 15-17");
  cmd->add_option("--set", o->overrides,
                  "Override a run config key, for the run and every scan point, e.g. --set "
                  "bonds.break_distance=0.01 (repeatable)");
  cmd->callback([o, &exit_code] {
    namespace fs = std::filesystem;
    const fs::path out(o->out);
    fs::create_directories(out);
    const std::string command = command_line(*o);
    const int stages = o->no_scan ? 4 : 5;
    int stage = 0;
    const auto announce = [&](const std::string& what) { fmt::print("[{}/{}] {}\n", ++stage, stages, what); };
    analysis::AnalysisResult r;
    {
      const io::FolderLock lock(out, command);
      const std::string config_text =
          o->config.empty() ? default_study_config : io::read_text_file(o->config, io::max_config_bytes);
      const fs::path config_file = out / "study.toml";
      io::write_file_atomically(config_file, config_text);

      std::vector<std::string> overrides = o->overrides;
      const fs::path run_folder = out / "run";
      overrides.push_back("output.folder=\"" + run_folder.string() + "\"");
      const auto config = loading::load_config(config_file, overrides);
      const Sample sample = loading::resolve_sample(config);

      const std::optional<scan::Plan> plan = plan_scan(*o, out, sample);

      announce("sample");
      save_sample(sample, out / "sample.rsample");
      const auto stats = compute_stats(sample);
      fmt::print("      {} particles, {} bonds, solid fraction {:.3f}, mean coordination {:.2f} -> {}\n",
                 stats.particles, stats.bonds, stats.solid_fraction, stats.mean_coordination,
                 (out / "sample.rsample").string());

      announce(fmt::format("tension test (k_n = {:g} N/mm, b_d = {:g} mm, {:g} mm/s)", config.bond_stiffness,
                           config.break_distance, config.speed));
      fs::remove_all(run_folder);
      const auto summary = loading::run_simulation(config, sample, run_folder, command);
      fmt::print(
          "      {} ({}) after {} steps at strain {:.4g} %, {} bonds broken, {:.3g} s, energy balance "
          "{:.2g}\n",
          summary.status, summary.stop_reason, summary.steps, summary.strain, summary.broken_bonds,
          summary.wall_seconds, summary.max_relative_energy_error);

      announce("precursor analysis");
      AnalyzeOptions analyze;
      analyze.curves = (run_folder / "curves.csv").string();
      r = analyze_and_write(analyze).result;

      if (plan) {
        announce(fmt::format("scan of {} points (k_n, b_d) of the same tissue for figures 15-17",
                             plan->points.size()));
        fs::remove_all(plan->folder);  // replaced, as the run folder is: the study's config may have changed
        scan::FarmOptions farm;
        farm.command = command;
        scan::run_scan(*plan, sample, farm);
      }
    }

    announce("figures and report");
    const auto report = report::write_report(out, "rupture report " + out.string());
    fmt::print("      {} figures in {}{}\n", report.figures, (out / "run" / "figures").string(),
               o->no_scan ? "" : " and " + (out / "scan" / "figures").string());
    print_outcome(fs::absolute(report.html).lexically_normal().string(), r);
    if (!r.accepted) exit_code = exit_rejected;
  });
}

}  // namespace rupture::cli
