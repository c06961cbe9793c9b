// cli/commands: one function per subcommand file; main() adds them all to the one `rupture` app.
// A command reports bad input by throwing InputError (exit 2), a failed computation by RunError
// (exit 1), and any other outcome by setting `exit_code` (e.g. 4: analysed but rejected).
#pragma once

#include <CLI/CLI.hpp>

namespace rupture::cli {

void add_fbm_command(CLI::App& app, int& exit_code);
void add_sample_command(CLI::App& app, int& exit_code);
void add_run_commands(CLI::App& app, int& exit_code);  // run, check
void add_bench_command(CLI::App& app, int& exit_code);
void add_analyze_command(CLI::App& app, int& exit_code);
void add_monitor_command(CLI::App& app, int& exit_code);
void add_study_command(CLI::App& app, int& exit_code);
void add_plot_command(CLI::App& app, int& exit_code);
void add_scan_command(CLI::App& app, int& exit_code);
void add_report_command(CLI::App& app, int& exit_code);

}  // namespace rupture::cli
