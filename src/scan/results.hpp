// scan/results: the scan's results table (results.csv): one row per point, every analysed quantity
// with its uncertainty, the run's outcome and the point's own choices (dt, ramp, stop strain).
// Owns: the column list, the row as JSON (what a point's result.json stores), writing and reading the
// table. Not: running points (scan/ledger, scan/farm) or drawing figures from the table.
//
// The table follows the project's CSV convention (docs/formats.md) with two additions that numbers
// alone cannot carry: columns without a `[unit]` hold text (status, stop_reason, class, why), and an
// empty field is a missing value (a quantity the analysis did not find, or a point not yet run).
// Text fields containing a comma, a double quote or a line break are quoted as in RFC 4180.
#pragma once

#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rupture::scan {

struct ResultColumn {
  std::string name;  // key in a point's "row" object and the header name
  std::string unit;  // "" for a text column
  bool physics;      // true: depends only on the point's inputs, never on jobs/threads/ranks/attempts
  std::string help;  // one line for docs and --help
  std::string header() const { return unit.empty() ? name : name + "[" + unit + "]"; }
};

// Every column, in file order. Names and units are stable: figures and user scripts read them.
//   point[1] k_n[N/mm] b_d[mm] dt[s] ramp_steps[1] max_strain[%] status stop_reason steps[1]
//   final_strain[%] broken_bonds[1] x_c[%] x_c_err[%] F_c[N] F_c_err[N] x_p[%] x_p_err[%]
//   Erate_max[mJ/%] Erate_max_err[mJ/%] x_m[%] x_m_err[%] E_max[mJ] E_max_err[mJ] delta_x[%]
//   delta_x_sd[%] delta_x_map[%] delta_x_lo68[%] delta_x_hi68[%] delta_x_lo95[%] delta_x_hi95[%]
//   Gamma[1] Gamma_err[1] A_r[1] A_r_err[1] alpha[1] class accepted[1] why wall_time[s]
const std::vector<ResultColumn>& result_columns();

// Point status values (column `status`).
namespace status {
inline constexpr const char* ok = "ok";                        // separated, analysed
inline constexpr const char* no_separation = "no_separation";  // stopped at max_strain/max_steps still whole
inline constexpr const char* unstable = "unstable";            // the run blew up (energy balance broke down)
inline constexpr const char* error = "error";                  // any other failure (reason in `why`)
inline constexpr const char* running = "running";              // only in --status and partial tables
inline constexpr const char* pending = "pending";
}  // namespace status

// The header line and one line per row; `rows` are JSON objects keyed by column name (a missing key
// or null is an empty field; numbers are written in the shortest form that reads back exactly, so
// equal numbers give equal bytes).
std::string format_results(const std::vector<nlohmann::json>& rows, const std::vector<std::string>& comments);

// A results.csv read back as text fields, with typed access by column name.
struct ResultsTable {
  std::string source;
  std::vector<std::string> comments;
  std::vector<std::string> header;             // full fields, e.g. "x_c[%]"
  std::vector<std::vector<std::string>> rows;  // rows[r][c], unquoted

  std::size_t require(std::string_view name) const;  // by name or full field; InputError if absent
  const std::string& text(std::size_t row, std::string_view name) const { return rows[row][require(name)]; }
  // The number in that field; nullopt when empty. InputError naming file, row and column otherwise.
  std::optional<double> number(std::size_t row, std::string_view name) const;
};

ResultsTable parse_results(std::string_view text, const std::string& source);
ResultsTable read_results(const std::filesystem::path& path);

// One row as the summaries read it (the scan figures, the claims): its parameters, outcome and the
// analysed quantities that are there.
struct PointOutcome {
  double k_n = 0.0, b_d = 0.0;         // N/mm, mm
  std::string status, mechanism, why;  // mechanism: the class column
  bool accepted = false;
  std::optional<double> x_c, x_c_err, delta_x, delta_lo68, delta_hi68, delta_lo95, alpha, A_r, A_r_err, gamma;

  // Separated, analysed and accepted, with a positive x_c: a point of figures 16 and 17.
  bool analysed() const { return status == scan::status::ok && accepted && x_c && *x_c > 0.0; }
  // Separated and analysed, but rejected; ductile-like when the analysis said so first.
  bool rejected() const { return status == scan::status::ok && !accepted; }
  bool ductile_like() const { return why.rfind("ductile-like", 0) == 0; }
};

// Every row that has its k_n and b_d, in table order.
std::vector<PointOutcome> read_outcomes(const ResultsTable& table);

}  // namespace rupture::scan
