// analysis/curve_file: the analysis of one curve file as `rupture analyze` does it — read the curve
// (and the breaks.csv beside it), analyse it, and build the analysis.json document with the inputs
// and version. Shared by `rupture analyze`, `rupture study` and the scan's points.
// Not: writing or printing (the callers do).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "analysis/analysis.hpp"

namespace rupture::analysis {

struct CurveFileInputs {
  std::filesystem::path curves;
  std::string breaks;      // bond-break table; empty: breaks.csv beside the curves, if present
  bool no_breaks = false;  // ignore any breaks table
  ColumnChoice columns;
  AnalysisOptions options;
};

struct CurveFileAnalysis {
  AnalysisResult result;
  nlohmann::json document;  // tool, version, inputs, then to_json(result)
};

// Throws InputError for unreadable or malformed input; a rejected curve is a normal outcome.
CurveFileAnalysis analyze_curve_file(const CurveFileInputs& inputs, const std::string& tool);

}  // namespace rupture::analysis
