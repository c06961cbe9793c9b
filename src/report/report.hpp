// report: the self-contained report.html of a run, scan or study folder — its figures embedded as data: URIs,
// the analysis numbers in tables with units and uncertainties, the run's facts and resolved config.
// Owns: the page and its HTML helpers. Not: drawing figures (figures/) or analysing curves (analysis/).
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace rupture::report {

// Standard base64 (RFC 4648, with '=' padding), for data: URIs.
std::string base64(std::string_view bytes);

struct ReportResult {
  std::filesystem::path html;  // FOLDER/report.html
  std::size_t figures = 0;     // pictures embedded
};

// Draws the folder's figures into FOLDER/figures (PNG, SVG and PDF, via figures::plot) and writes
// FOLDER/report.html atomically. FOLDER is a run folder (curves.csv [+ analysis.json, breaks.csv,
// run.json, snapshots/]), a scan folder (results.csv, scan.json) or a study folder (study.toml, run/ and
// scan/: the run's report with the scan's figures 15-17 and claims). `command` is recorded in the page.
// Bad input throws InputError; gnuplot or I/O trouble RunError.
ReportResult write_report(const std::filesystem::path& folder, const std::string& command);

}  // namespace rupture::report
