// cli/main: the `rupture` binary. Parses the command line, dispatches to one subcommand, and turns
// errors into one-line messages and exit codes (0 ok, 1 failed, 2 bad input, 4 rejected).
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <csignal>
#include <cstdio>
#include <exception>
#include <string>

#include "cli/commands.hpp"
#include "core/error.hpp"
#include "rupture/version.hpp"

namespace {

// The first word of the command line that names no subcommand where one is expected ("rupture nosuch",
// "rupture fbm nosuch"), as a one-line message listing the ones there are; empty when every word fits.
// CLI11 alone would only say "A subcommand is required".
std::string unknown_subcommand(const CLI::App& app, int argc, char** argv) {
  const CLI::App* at = &app;
  std::string path = "rupture";
  for (int i = 1; i < argc; ++i) {
    const std::string word = argv[i];
    const auto subcommands = at->get_subcommands([](const CLI::App*) { return true; });
    if (word.empty() || word[0] == '-' || subcommands.empty()) return {};
    const auto match = std::find_if(subcommands.begin(), subcommands.end(),
                                    [&](const CLI::App* s) { return s->get_name() == word; });
    if (match == subcommands.end()) {
      std::string names;
      for (const auto* s : subcommands) names += (names.empty() ? "" : ", ") + s->get_name();
      return fmt::format("unknown subcommand '{}' of {}; the subcommands are {} (see {} --help)", word, path,
                         names, path);
    }
    at = *match;
    path += " " + word;
  }
  return {};
}

}  // namespace

int main(int argc, char** argv) {
  using namespace rupture;
  // A write past the file size limit (ulimit -f) then fails with EFBIG, handled like a full disk
  // (a message, run.json marked failed, the checkpoints kept), instead of killing the process.
  std::signal(SIGXFSZ, SIG_IGN);
  CLI::App app{
      "rupture: fiber bundle models, bonded-particle DEM tension tests and the precursor of failure"};
  app.set_version_flag("--version", version_string);
  app.require_subcommand(1);
  int exit_code = exit_ok;
  cli::add_study_command(app, exit_code);
  cli::add_fbm_command(app, exit_code);
  cli::add_sample_command(app, exit_code);
  cli::add_run_commands(app, exit_code);
  cli::add_bench_command(app, exit_code);
  cli::add_analyze_command(app, exit_code);
  cli::add_monitor_command(app, exit_code);
  cli::add_plot_command(app, exit_code);
  cli::add_scan_command(app, exit_code);
  cli::add_report_command(app, exit_code);
  if (const std::string unknown = unknown_subcommand(app, argc, argv); !unknown.empty()) {
    fmt::print(stderr, "rupture: error: {}\n", unknown);
    return exit_bad_input;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return exit_bad_input;
  } catch (const InputError& e) {
    fmt::print(stderr, "rupture: error: {}\n", e.what());
    return exit_bad_input;
  } catch (const RunError& e) {
    fmt::print(stderr, "rupture: failed: {}\n", e.what());
    return exit_failure;
  } catch (const std::exception& e) {
    fmt::print(stderr, "rupture: internal error: {}\n", e.what());
    return exit_failure;
  }
  return exit_code;
}
