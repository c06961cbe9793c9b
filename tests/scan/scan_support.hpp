// tests/scan/scan_support: what the scan suites share — shell quoting for run_rupture and the physics
// columns of a results.csv, which must be the same bytes however a scan was run.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "scan/results.hpp"

namespace rupture::scan::test_support {

inline std::string shell_quoted(const std::filesystem::path& p) { return "'" + p.string() + "'"; }

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

}  // namespace rupture::scan::test_support
