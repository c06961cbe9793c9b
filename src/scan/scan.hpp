// scan: parameter scans over (k_n, b_d) on one sample (paper section 5): the scan config, its ordered
// points with their per-point rules (dt, ramp length, stop strain), and the plan every process of a
// scan agrees on. Runs, resumes and aggregation are in scan/ledger.hpp and scan/farm.hpp.
// Not: the DEM run itself (loading/run) or the curve analysis (analysis/).
#pragma once

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "loading/config.hpp"
#include "sample/sample.hpp"

namespace rupture::scan {

// Values from `from` to `to` (both included), equally spaced in log: from · (to/from)^(i/(count−1)).
struct LogRange {
  double from = 0.0, to = 0.0;
  int count = 0;
};

struct ScanConfig {
  std::filesystem::path file;                     // the scan config (for messages and relative paths)
  std::filesystem::path base;                     // [scan] base: run config every point starts from
  std::filesystem::path output = "scan";          // [scan] output: scan folder, relative to the working dir
  std::vector<std::string> set;                   // [scan] set: extra "section.key=value" overrides
  std::vector<std::string> sample;                // [sample]: overrides of the base config's sample
  std::optional<LogRange> grid_k_n, grid_b_d;     // [grid] k_n (N/mm), b_d (mm)
  std::vector<std::pair<double, double>> listed;  // [[points]] (k_n N/mm, b_d mm)
  // [rules]
  std::optional<double> dt;               // s; empty: "auto" = time.safety x critical dt of each point
  std::string ramp = "scaled";            // "scaled" | "strain" | "base"
  double ramp_fraction = 0.1;             // "strain": the ramp covers this fraction of the first-break strain
  std::int64_t ramp_steps = 10000;        // steps at b_d = ramp_b_d
  double ramp_b_d = 0.5;                  // mm
  double ramp_exponent = 1.0;             // 1: steps ∝ (ramp_b_d / b_d)^exponent
  std::int64_t ramp_min_steps = 10000;    // steps
  std::int64_t ramp_max_steps = 1000000;  // steps
  std::string max_strain = "base";        // "base" | "scaled"
  double max_strain_factor = 20.0;        // 1: stop at this multiple of the first-break strain
  double max_strain_min = 1.0;            // %: never stop earlier than this
  std::string interval = "base";          // "base" | "scaled": curve rows every output.interval steps,
  double rows_to_first_break = 400.0;     // or so that this many rows lie below the first-break strain
};

// Reads a scan config; relative paths (base, sample.file) are taken from the config's folder.
// Unknown keys and bad values throw InputError naming the file and key with the fix.
ScanConfig load_scan_config(const std::filesystem::path& file);
nlohmann::json to_json(const ScanConfig& config);
// Every [rules] key with its unit, plausible range and default, as a commented TOML document
// (rupture scan --help-config).
std::string rules_reference();

// The base run config with the scan's sample and `set` overrides (what every point starts from).
loading::RunConfig base_config(const ScanConfig& config);

// Values rounded to 6 significant digits, so a point's folder name is its exact parameters.
std::vector<double> log_spaced(const LogRange& range);

struct Point {
  std::size_t index = 0;
  double k_n = 0.0, b_d = 0.0;       // N/mm, mm
  std::string name;                  // folder under points/, e.g. "kn_1000_bd_0.005"
  std::int64_t ramp_steps = 0;       // steps
  double max_strain = 0.0;           // %
  std::int64_t output_interval = 0;  // steps between curve rows (0: the base config's, plans of 0.1)
};

// The most points one scan folder takes (a grid of 10^8 would only exhaust memory).
inline constexpr std::size_t max_points = 100000;

struct Plan {
  std::filesystem::path folder;             // the scan folder
  std::filesystem::path base;               // the base run config
  loading::RunConfig base_config;           // it with the scan's [sample] keys and set, read once
  std::vector<std::string> base_overrides;  // those keys as the scan config wrote them (for commands)
  std::optional<double> dt;                 // s, [rules] dt for every point; empty: "auto"
  std::uint64_t sample_fingerprint = 0;     // loading::sample_fingerprint of the sample every point runs on
  nlohmann::json scan_config;               // to_json(ScanConfig), for scan.json
  std::vector<Point> points;                // grid (k_n slowest) then the list; duplicates dropped
};

std::string point_name(double k_n, double b_d);

// Builds the plan for `sample` (the base config's): every point's config is loaded (and so checked)
// now, before anything runs, and a given [rules] dt is checked against every point's stability
// limit. Throws InputError when the output folder is a file.
Plan make_plan(const ScanConfig& config, const Sample& sample);

// A sample fingerprint as 16 hex digits (JSON numbers lose the last bits of a 64-bit integer).
std::string fingerprint_text(std::uint64_t fingerprint);

// The keys a point sets over the base config, as typed values ({"bonds": {"stiffness": 1e3}, ...}).
nlohmann::json point_settings(const Plan& plan, const Point& point, int threads);
// The run config of one point, with `threads` OpenMP threads: the base config with its settings.
loading::RunConfig point_config(const Plan& plan, const Point& point, int threads);
// "rupture run BASE --set ..." that reproduces the point by hand.
std::string point_command(const Plan& plan, const Point& point, int threads);

// plan.json in the scan folder: lets --status and --collect work from the folder alone.
nlohmann::json to_json(const Plan& plan);
Plan plan_from_json(const nlohmann::json& document, const std::filesystem::path& folder);
void write_plan(const Plan& plan);
Plan read_plan(const std::filesystem::path& folder);

}  // namespace rupture::scan
