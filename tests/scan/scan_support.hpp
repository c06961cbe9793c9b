// tests/scan/scan_support: what the scan suites share — shell quoting for run_rupture, the physics
// columns of a results.csv (the same bytes however a scan was run) and running the SLURM examples.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "scan/results.hpp"
#include "support/tool.hpp"

namespace rupture::scan::test_support {

using rupture::testing::shell_quoted;

// The physics columns of a results.csv (every column but wall_time), row by row, as text: equal
// strings mean equal bytes.
inline std::vector<std::string> physics(const std::filesystem::path& results) {
  const ResultsTable table = read_results(results);
  std::vector<std::string> lines;
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    std::string line;
    for (const auto& column : result_columns())
      if (column.physics) line += table.text(r, column.name) + ",";
    lines.push_back(line);
  }
  return lines;
}

struct ScriptRun {
  int exit_code = -1;
  std::string out;  // stdout and stderr together
};

// Runs one of examples/slurm/ with bash in `folder` as a scheduler would, `environment` being
// "NAME=value ..." words (the scheduler's variables and the script's RUPTURE, SCAN_CONFIG, ...).
inline ScriptRun run_script(const std::string& script, const std::filesystem::path& folder,
                            const std::string& environment) {
  const auto log = folder / (std::filesystem::path(script).stem().string() + ".log");
  const std::string command = "cd " + shell_quoted(folder) + " && CI=1 RUPTURE='" RUPTURE_BINARY "' " +
                              environment + " bash " + shell_quoted(RUPTURE_EXAMPLES_DIR "slurm/" + script) +
                              " </dev/null >" + shell_quoted(log) + " 2>&1";
  const int status = std::system(command.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, rupture::testing::slurp(log)};
}

}  // namespace rupture::scan::test_support
