// cli/run_command: `rupture run CONFIG.toml` (the DEM tension test), `rupture run --resume DIR`
// (continue an interrupted or killed run from its newest checkpoint) and `rupture check
// CONFIG.toml` (the resolved config, dt with its inputs, speed ratio, estimates and warnings,
// without stepping). Owns option parsing and terminal text; the run itself is loading/run.
// Exit codes: 0 finished, 1 failed (unstable, a write failed), 2 bad input, 128 + signal when
// SIGINT (130) or SIGTERM (143) stopped the run after writing a checkpoint.
#include <fmt/format.h>

#include <csignal>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "core/error.hpp"
#include "core/units.hpp"
#include "loading/config.hpp"
#include "loading/interrupt.hpp"
#include "loading/run.hpp"

namespace rupture::cli {

namespace {

struct RunOptions {
  std::string config;
  std::vector<std::string> overrides;
  std::string output;
  std::string resume;  // run folder to continue
  bool overwrite = false;
  bool help_config = false;
};

void add_config_options(CLI::App& command, RunOptions& options) {
  command.add_option("config", options.config, "run configuration (TOML); see --help-config");
  command.add_option("--set", options.overrides, "override a key: --set bonds.stiffness=1e4 (repeatable)");
  command.add_flag("--help-config", options.help_config, "print every config key with its unit and default");
}

loading::RunConfig load(const RunOptions& options) {
  if (options.config.empty())
    throw InputError("rupture run", "no config file given",
                     "run `rupture run CONFIG.toml` (see --help-config)");
  std::vector<std::string> overrides = options.overrides;
  if (!options.output.empty()) overrides.push_back("output.folder=\"" + options.output + "\"");
  return loading::load_config(options.config, overrides);
}

std::string command_line(const std::string& name, const RunOptions& options) {
  std::string line = "rupture " + name + " " + options.config;
  for (const auto& o : options.overrides) line += " --set " + o;
  if (!options.output.empty()) line += " --out " + options.output;
  if (options.overwrite) line += " --overwrite";
  return line;
}

void print_check(const loading::RunConfig& config, const Sample& sample, const loading::RunPlan& plan) {
  fmt::print("# resolved configuration\n{}\n\n", loading::to_json(config).dump(2));
  fmt::print("sample: {} particles, {} bonds\n", sample.size(), sample.bonds.size());
  fmt::print(
      "dt: {:.4g} s ({}), critical dt {:.4g} s from the stiffest particle (springs summing to {:.4g} N/mm on "
      "{:.4g} g), safety {:g}\n",
      plan.dt, plan.dt_auto ? "auto" : "given", plan.critical_dt, plan.stiffest_spring_sum,
      units::mass_to_grams(plan.stiffest_mass), config.dt_safety);
  fmt::print("ramp: {} steps = {:.4g} s; plate separation l0 = {:.4g} mm\n", config.ramp_steps,
             plan.ramp_time, plan.plate_separation);
  fmt::print("plate speed / wave speed: {:.3g} ({:g} mm/s vs {:.4g} mm/s)\n", plan.speed_ratio, config.speed,
             plan.wave_speed);
  fmt::print(
      "first bond break expected near strain {:.3g} % (the most stretched bond under an affine pull)\n",
      plan.first_break_strain);
  fmt::print(
      "estimate: at most {} steps (to stop.max_strain {} % or stop.max_steps), about {:.3g} s of wall time\n",
      plan.estimated_steps, config.max_strain, plan.estimated_seconds);
  fmt::print("memory: {:.3g} MB ({:.0f} bytes per particle)\n", double(plan.memory_bytes) / 1e6,
             double(plan.memory_bytes) / double(std::max<std::size_t>(1, sample.size())));
  for (const auto& w : plan.warnings) fmt::print("warning: {}\n", w);
}

}  // namespace

void add_run_commands(CLI::App& app, int& exit_code) {
  auto run_options = std::make_shared<RunOptions>();
  auto* run = app.add_subcommand("run", "Run a DEM tension test from a TOML config");
  add_config_options(*run, *run_options);
  run->add_option("-o,--out,--output", run_options->output, "output folder (overrides output.folder)");
  run->add_flag("--overwrite", run_options->overwrite,
                "replace the outputs of a run that ended in the output folder (a folder holding other "
                "files, or an unfinished run, is still refused)");
  run->add_option("--resume", run_options->resume,
                  "continue the interrupted or killed run in this folder from its newest checkpoint");
  run->callback([run_options, &exit_code] {
    if (run_options->help_config) {
      fmt::print("{}", loading::config_reference());
      return;
    }
    const auto& options = *run_options;
    if (!options.resume.empty() && (!options.config.empty() || !options.overrides.empty() ||
                                    !options.output.empty() || options.overwrite))
      throw InputError("rupture run --resume", "takes no config, --set, -o/--out or --overwrite",
                       "a resumed run keeps the config and folder it began with: run `rupture run --resume " +
                           options.resume + "` alone");
    loading::install_interrupt_handlers();
    loading::RunSummary summary;
    std::string folder;
    if (!options.resume.empty()) {
      folder = options.resume;
      summary = loading::resume_simulation(folder, "rupture run --resume " + folder);
    } else {
      const auto config = load(options);
      const Sample sample = loading::resolve_sample(config);
      folder = config.output_folder;
      summary = loading::run_simulation(
          config, sample, folder, command_line("run", options),
          {.existing = options.overwrite ? loading::Existing::overwrite : loading::Existing::refuse});
    }
    if (summary.signal != 0) {
      fmt::print(stderr,
                 "interrupted by {} after step {} (strain {:.4g} %); checkpoint {} written; continue with "
                 "`rupture run --resume {}`\n",
                 summary.signal == SIGINT ? "SIGINT" : "SIGTERM", summary.steps, summary.strain,
                 summary.checkpoint.string(), folder);
      exit_code = loading::interrupt_exit_code(summary.signal);
      return;
    }
    fmt::print(
        "{}: {} after {} steps at strain {:.4g} %, {} bonds broken, {:.3g} s; energy balance error {:.3g} of "
        "the plate work; outputs in {}\n",
        summary.status, summary.stop_reason, summary.steps, summary.strain, summary.broken_bonds,
        summary.wall_seconds, summary.max_relative_energy_error, folder);
    exit_code = exit_ok;
  });

  auto check_options = std::make_shared<RunOptions>();
  auto* check =
      app.add_subcommand("check", "Check a run config: resolved keys, dt, speed ratio, estimates, warnings");
  add_config_options(*check, *check_options);
  check->callback([check_options] {
    if (check_options->help_config) {
      fmt::print("{}", loading::config_reference());
      return;
    }
    const auto config = load(*check_options);
    const Sample sample = loading::resolve_sample(config);
    const dem::System system(sample, config.dem_params(sample.density));
    print_check(config, sample, loading::plan_run(config, system, sample));
  });
}

}  // namespace rupture::cli
