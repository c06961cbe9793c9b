// cli/analyze_command: the analysis of one curve file as `rupture analyze` does it — read the curve
// (and breaks.csv beside it), analyse, write analysis.json with the inputs and version, print the
// summary — shared with `rupture study`.
#pragma once

#include <CLI/CLI.hpp>
#include <filesystem>
#include <string>

#include "analysis/analysis.hpp"

namespace rupture::cli {

struct AnalyzeOptions {
  std::string curves, output, breaks;
  bool no_breaks = false;
  analysis::ColumnChoice columns;
  std::string filter = "butterworth";
  // Words of analysis/option_words.hpp, the analysis's defaults until the command line names others.
  std::string delay_method = analysis::to_string(analysis::AnalysisOptions{}.delay_method);
  std::string force_peak_form = analysis::to_string(analysis::AnalysisOptions{}.force_peak_form);
  analysis::AnalysisOptions analysis;
};

struct AnalyzeOutcome {
  analysis::AnalysisResult result;
  std::filesystem::path output;  // the analysis.json written
};

// --strain/--force/--energy, their scales and units: how `analyze` and `monitor` name the columns
// of a table that rupture did not write.
void add_curve_column_options(CLI::App& cmd, analysis::ColumnChoice& columns);

// Throws InputError for unreadable or malformed input; a rejected curve is a normal outcome.
AnalyzeOutcome analyze_and_write(const AnalyzeOptions& options);

}  // namespace rupture::cli
