// cli/report_command: `rupture report FOLDER` — redraws the figures of a run or scan folder and writes
// FOLDER/report.html, one self-contained page (figures embedded, numbers in tables) that opens in any
// browser without a server. Exit 0 written, 2 bad input, 1 gnuplot or I/O trouble.
#include <fmt/format.h>

#include <filesystem>
#include <memory>
#include <string>

#include "cli/commands.hpp"
#include "report/report.hpp"

namespace rupture::cli {

void add_report_command(CLI::App& app, int& /*exit_code*/) {
  auto folder = std::make_shared<std::string>();
  auto* command = app.add_subcommand("report",
                                     "Write FOLDER/report.html: the figures, analysis numbers, run facts and "
                                     "config of a run or scan folder");
  command
      ->add_option("folder", *folder,
                   "Run folder (curves.csv, analysis.json, run.json) or scan folder (results.csv)")
      ->required();
  command->callback([folder] {
    const auto result = report::write_report(*folder, "rupture report " + *folder);
    fmt::print("wrote {} ({} figures embedded)\n", result.html.string(), result.figures);
  });
}

}  // namespace rupture::cli
