// cli/study_command: `rupture study` — the whole study in one command, as `scripts/study` runs it:
// a reduced tissue is generated, pulled to separation, analysed for the precursor, plotted and reported.
// The default config is embedded below and written into the study folder, so the study records
// exactly what it ran; `--config` and `--set` change it.
#include <fmt/format.h>

#include <filesystem>
#include <memory>
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

struct StudyOptions {
  std::string out = "study";
  std::string config;
  std::vector<std::string> overrides;
};

}  // namespace

void add_study_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<StudyOptions>();
  auto* cmd = app.add_subcommand(
      "study",
      "The whole study on the default reduced tissue: generate, pull to separation, analyse, plot, report");
  cmd->add_option("-o,--out", o->out, "Study folder (created; its run/ folder is replaced)");
  cmd->add_option("--config", o->config, "Run config to use instead of the embedded default (TOML)");
  cmd->add_option("--set", o->overrides,
                  "Override a config key, e.g. --set bonds.break_distance=0.01 (repeatable)");
  cmd->callback([o, &exit_code] {
    namespace fs = std::filesystem;
    const fs::path out(o->out);
    fs::create_directories(out);
    const io::FolderLock lock(out, "rupture study --out " + o->out);
    const std::string config_text = o->config.empty() ? default_study_config : io::read_text_file(o->config, io::max_config_bytes);
    const fs::path config_file = out / "study.toml";
    io::write_file_atomically(config_file, config_text);

    std::vector<std::string> overrides = o->overrides;
    const fs::path run_folder = out / "run";
    overrides.push_back("output.folder=\"" + run_folder.string() + "\"");
    const auto config = loading::load_config(config_file, overrides);

    fmt::print("[1/4] sample\n");
    const Sample sample = loading::resolve_sample(config);
    save_sample(sample, out / "sample.rsample");
    const auto stats = compute_stats(sample);
    fmt::print("      {} particles, {} bonds, solid fraction {:.3f}, mean coordination {:.2f} -> {}\n",
               stats.particles, stats.bonds, stats.solid_fraction, stats.mean_coordination,
               (out / "sample.rsample").string());

    fmt::print("[2/4] tension test (k_n = {:g} N/mm, b_d = {:g} mm, {:g} mm/s)\n", config.bond_stiffness,
               config.break_distance, config.speed);
    fs::remove_all(run_folder);
    std::string command = "rupture study --out " + o->out;
    if (!o->config.empty()) command += " --config " + o->config;
    for (const auto& s : o->overrides) command += " --set " + s;
    const auto summary = loading::run_simulation(config, sample, run_folder, command);
    fmt::print(
        "      {} ({}) after {} steps at strain {:.4g} %, {} bonds broken, {:.3g} s, energy balance {:.2g}\n",
        summary.status, summary.stop_reason, summary.steps, summary.strain, summary.broken_bonds,
        summary.wall_seconds, summary.max_relative_energy_error);

    fmt::print("[3/4] precursor analysis\n");
    AnalyzeOptions analyze;
    analyze.curves = (run_folder / "curves.csv").string();
    const auto outcome = analyze_and_write(analyze);
    const auto& r = outcome.result;

    fmt::print("[4/4] figures and report\n");
    const auto report = report::write_report(run_folder, "rupture report " + run_folder.string());
    fmt::print("      {} figures in {}\n", report.figures, (run_folder / "figures").string());
    const std::string html = fs::absolute(report.html).lexically_normal().string();
    if (r.x_p && r.x_c && r.delay) {
      fmt::print(
          "report: {}; precursor: x_p = {:.3g} %, x_c = {:.3g} % (delta_x = {:.2g} +- {:.1g} %, 95 % "
          "[{:.2g}, {:.2g}] %): {}{}\n",
          html, r.x_p->value, r.x_c->value, r.delay->mean, r.delay->sd, r.delay->ci95_low, r.delay->ci95_high,
          analysis::precursor_order(r.delay->ci95_low, r.delay->ci95_high),
          r.accepted ? "" : "; analysis rejected: " + r.rejection);
    } else {
      fmt::print("report: {}; no precursor found ({})\n", html, r.accepted ? "no peak" : r.rejection);
    }
    if (!r.accepted) exit_code = exit_rejected;
  });
}

}  // namespace rupture::cli
