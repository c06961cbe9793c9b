#include "report/report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "analysis/analysis.hpp"
#include "core/error.hpp"
#include "figures/figures.hpp"
#include "io/atomic_file.hpp"
#include "io/file_lock.hpp"
#include "io/markup.hpp"
#include "loading/config.hpp"
#include "rupture/version.hpp"
#include "scan/claims.hpp"
#include "scan/results.hpp"

namespace rupture::report {

namespace fs = std::filesystem;
using nlohmann::json;

std::string base64(std::string_view bytes) {
  static constexpr char alphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 3 <= bytes.size(); i += 3) {
    const unsigned v = static_cast<unsigned char>(bytes[i]) << 16 |
                       static_cast<unsigned char>(bytes[i + 1]) << 8 |
                       static_cast<unsigned char>(bytes[i + 2]);
    for (int shift : {18, 12, 6, 0}) out += alphabet[(v >> shift) & 63u];
  }
  if (const std::size_t rest = bytes.size() - i; rest > 0) {
    unsigned v = static_cast<unsigned char>(bytes[i]) << 16;
    if (rest == 2) v |= static_cast<unsigned char>(bytes[i + 1]) << 8;
    out += alphabet[(v >> 18) & 63u];
    out += alphabet[(v >> 12) & 63u];
    out += rest == 2 ? alphabet[(v >> 6) & 63u] : '=';
    out += '=';
  }
  return out;
}

namespace {

constexpr const char* style_sheet =
    R"(body{font-family:sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;color:#222;line-height:1.45}
h1{font-size:1.6em;border-bottom:2px solid #888}h2{font-size:1.25em;margin-top:2em;border-bottom:1px solid #ccc}
table{border-collapse:collapse;margin:0.5em 0 1em}th,td{border:1px solid #ccc;padding:0.25em 0.6em;text-align:left;vertical-align:top}
th{background:#f0f0f0}td.num{text-align:right;font-variant-numeric:tabular-nums}
figure{margin:1em 0}figure img{max-width:100%;height:auto;border:1px solid #ddd}figcaption{font-size:0.92em;color:#444}
.summary{font-size:1.1em;background:#f6f6ee;border-left:4px solid #b08d00;padding:0.6em 1em}
.scroll{overflow-x:auto}code{background:#f3f3f3;padding:0 0.2em}td{overflow-wrap:anywhere}
.row{display:flex;flex-wrap:wrap;gap:1em}.row figure{flex:1 1 420px;margin:0}
)";

std::string number_text(double value) {
  if (!std::isfinite(value)) return "–";
  return fmt::format("{:.4g}", value);
}

// One table: header cells and rows of cells (already escaped HTML); `numeric` columns align right.
std::string table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows,
                  const std::vector<bool>& numeric = {}) {
  std::string html = "<div class=\"scroll\"><table>\n<thead><tr>";
  for (const auto& h : header) html += "<th>" + h + "</th>";
  html += "</tr></thead>\n<tbody>\n";
  for (const auto& row : rows) {
    html += "<tr>";
    for (std::size_t c = 0; c < row.size(); ++c) {
      const bool is_number = c < numeric.size() && numeric[c];
      html += (is_number ? "<td class=\"num\">" : "<td>") + row[c] + "</td>";
    }
    html += "</tr>\n";
  }
  return html + "</tbody>\n</table></div>\n";
}

// A quantity of rupture's JSON ({"value", "unit"}, io/quantity.hpp), or null.
bool is_quantity(const json& q) { return q.is_object() && q.contains("value") && q.contains("unit"); }

// A number as text, or "–" when it is missing (null, absent, not a number).
std::string number_or_dash(const json& v) { return v.is_number() ? number_text(v.get<double>()) : "–"; }

// The value of a quantity as text ("–" when null or missing).
std::string value_text(const json& q) { return number_or_dash(is_quantity(q) ? q["value"] : json()); }

std::string unit_text(const json& q) {
  return is_quantity(q) && q["unit"].is_string() ? io::escape_markup(q["unit"].get<std::string>()) : "";
}

// A measured analysis quantity {"value", "error", "unit"} as (value, ± error, unit) cells.
std::vector<std::string> measured_row(const std::string& name, const std::string& meaning, const json& m) {
  if (!is_quantity(m)) return {io::escape_markup(name), io::escape_markup(meaning), "not found", "", ""};
  const auto error = m.contains("error") && m["error"].is_number() ? m["error"].get<double>() : NAN;
  return {io::escape_markup(name), io::escape_markup(meaning), value_text(m),
          std::isfinite(error) ? "± " + number_text(error) : "", unit_text(m)};
}

// Nested JSON flattened to "a.b.c" keys and their values as text, in key order; a quantity is one
// entry with its unit; arrays of numbers are one short list (4 digits), so a histogram fits the page.
struct FlatEntry {
  std::string key, value;
  std::string unit;  // a quantity's; 1 for a bare number; empty for text and flags
  bool quantity = false;
};
void flatten(const json& value, const std::string& prefix, std::vector<FlatEntry>& entries) {
  if (is_quantity(value)) {
    std::vector<FlatEntry> inner;
    flatten(value["value"], prefix, inner);
    entries.push_back({prefix, inner.front().value, value["unit"].get<std::string>(), true});
    return;
  }
  if (value.is_object() && !value.empty()) {
    for (const auto& [key, child] : value.items())
      flatten(child, prefix.empty() ? key : prefix + "." + key, entries);
    return;
  }
  std::string text = value.is_string() ? value.get<std::string>() : value.dump();
  if (value.is_number_float()) text = fmt::format("{:.6g}", value.get<double>());
  if (value.is_array() &&
      std::all_of(value.begin(), value.end(), [](const json& v) { return v.is_number(); })) {
    text.clear();
    for (const auto& v : value) text += (text.empty() ? "" : ", ") + number_text(v.get<double>());
    text = "[" + text + "]";
  }
  // A bare number is dimensionless (docs/formats.md); text and flags have no unit.
  entries.push_back({prefix, text, value.is_number() ? "1" : "", false});
}

// A key/value/unit table of nested JSON. The unit is the quantity's; else `unit_of(flattened key)`
// when given (a config's keys), else 1 for a bare number.
std::string key_value_table(const json& value,
                            const std::function<std::string(const std::string&)>& unit_of = nullptr) {
  std::vector<FlatEntry> entries;
  flatten(value, "", entries);
  std::vector<std::vector<std::string>> rows;
  for (const auto& e : entries) {
    const std::string unit = unit_of && !e.quantity ? unit_of(e.key) : e.unit;
    rows.push_back({"<code>" + io::escape_markup(e.key) + "</code>", io::escape_markup(e.value),
                    io::escape_markup(unit)});
  }
  return table({"key", "value", "unit"}, rows);
}

// The folder's own name, also when it is given as "." or "run/".
std::string folder_name(const fs::path& folder) {
  std::error_code ignored;
  return fs::weakly_canonical(fs::absolute(folder), ignored).filename().string();
}

json read_json(const fs::path& file) {
  try {
    return json::parse(io::read_text_file(file));
  } catch (const json::exception& e) {
    throw InputError(file.string(), fmt::format("not valid JSON: {}", e.what()),
                     "rewrite it with the rupture command that made it");
  }
}

// The figures as <figure> elements with their captions, under `heading`; file names are given
// relative to the report's folder. `row` sets them side by side (two on a wide screen).
std::string figures_section(const std::vector<figures::Drawn>& drawn, const fs::path& report_folder,
                            std::size_t& count, const std::string& heading = "Figures", bool row = false) {
  std::string html = "<h2>" + heading + "</h2>\n";
  if (row) html += "<div class=\"row\">\n";
  for (const auto& figure : drawn) {
    const fs::path png = figure.png();
    if (png.empty()) continue;
    const std::string stem =
        (png.parent_path().lexically_relative(report_folder) / figure.name).generic_string();
    html += fmt::format(
        "<figure><img alt=\"{0}\" src=\"data:image/png;base64,{1}\">\n<figcaption><strong>{0}</strong>: {2} "
        "(data and gnuplot script: <code>{3}.dat</code>, <code>{3}.gp</code>)</figcaption></figure>\n",
        io::escape_markup(figure.name), base64(io::read_file(png)), io::escape_markup(figure.caption),
        io::escape_markup(stem));
    ++count;
  }
  if (row) html += "</div>\n";
  return html;
}

// Once the page has loaded, records on <body> how many figures decoded (data-figures="N of M loaded"),
// so a headless browser can tell a page whose pictures are broken from one that shows them all.
constexpr const char* figure_check = R"(window.addEventListener("load", function () {
  var images = Array.prototype.slice.call(document.images);
  var loaded = images.filter(function (img) { return img.complete && img.naturalWidth > 0; }).length;
  document.body.setAttribute("data-figures", loaded + " of " + images.length + " loaded");
});
)";

std::string page(const std::string& title, const std::string& body) {
  return fmt::format(
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta "
      "charset=\"utf-8\">\n<title>{}</title>\n<style>\n{}</style>\n"
      "<script>\n{}</script>\n</head>\n<body>\n{}</body>\n</html>\n",
      io::escape_markup(title), style_sheet, figure_check, body);
}

std::string provenance(const fs::path& folder, const std::string& command) {
  return fmt::format(
      "<p>Written by rupture {} (<code>{}</code>) from the folder <code>{}</code>. Every number below is "
      "read from the files of that folder; the figures are redrawn from them.</p>\n",
      io::escape_markup(version_string), io::escape_markup(command),
      io::escape_markup(fs::absolute(folder).string()));
}

// The one sentence a reader wants first: where the precursor was and how far ahead of failure.

// The class, or why there is none: a rejected curve carries no class.
std::string mechanism_text(const json& mechanism) {
  if (mechanism["class"].is_string()) return io::escape_markup(mechanism["class"].get<std::string>());
  return "none (rejected; its features say " +
         io::escape_markup(mechanism.value("features_say", std::string("?"))) + ")";
}

// Whether analysis.json says δ_x's factors passed a held-out check (docs/analysis.md, Calibration);
// false for files that do not say.
bool interval_calibrated(const json& delta) {
  return delta.contains("interval_scales") && delta["interval_scales"].value("calibrated", false);
}

// Nothing where δ_x's intervals are calibrated; else that they are not, and why where the reason is
// the curve's white noise below the level from which the white factors were checked, or a sharp
// collapse filtered apart from the loading.
std::string uncalibrated_because(const json& analysis) {
  const auto& delta = analysis["delta_x"];
  if (interval_calibrated(delta)) return "";
  // The level first: below it no factor is calibrated, with a collapse or without.
  const auto& scales = delta.value("interval_scales", json::object());
  const double level = scales.value("white_share", std::numeric_limits<double>::quiet_NaN());
  if (level < analysis::white_factors_checked_from) {
    return fmt::format(
        "; its intervals are not calibrated: the curve's white noise, {} % of its peak, lies below the {:g} "
        "% "
        "from which the white factors were checked (docs/analysis.md)",
        number_text(100.0 * level), 100.0 * analysis::white_factors_checked_from);
  }
  if (const auto onset = analysis.find("collapse_onset"); onset != analysis.end() && onset->is_object()) {
    return fmt::format(
        "; its intervals are not calibrated: the curve ends in a collapse too sharp for the filter (from "
        "{} {}), filtered apart from the loading, where delta_x's intervals are calibrated only on {} (far: "
        "{:g} % of x_c or more past the force peak), and not where the noise model read a ringing "
        "(docs/analysis.md)",
        number_text(onset->at("value").get<double>()), io::escape_markup(onset->value("unit", "")),
        analysis::calibrated_collapse_cells(analysis::collapse_delta_scales),
        100.0 * analysis::collapse_near_closeness);
  }
  return "; its intervals are not calibrated";
}

std::string run_summary(const json& analysis) {
  if (analysis.is_null()) {
    return "<p class=\"summary\">Not analysed yet: run <code>rupture analyze curves.csv</code> in this "
           "folder, then "
           "<code>rupture report</code> again.</p>\n";
  }
  std::string text;
  const auto& x_p = analysis["x_p"];
  const auto& x_c = analysis["x_c"];
  const auto& delta = analysis["delta_x"];
  if (x_p.is_object() && x_c.is_object() && delta.is_object()) {
    const std::string unit = io::escape_markup(delta.value("unit", ""));
    const auto ci95 = delta.at("ci95");
    text = fmt::format(
        "Precursor: the energy rate peaks at x<sub>p</sub> = {} {u}, the force at "
        "x<sub>c</sub> = {} {u}; delay δ<sub>x</sub> = {} ± {} {u} (95 % interval [{}, {}] {u}{}): {}.",
        value_text(x_p), value_text(x_c), number_text(delta["mean"].get<double>()),
        number_text(delta["sd"].get<double>()), number_text(ci95.at(0).get<double>()),
        number_text(ci95.at(1).get<double>()), analysis::calibration_mark(interval_calibrated(delta)),
        io::escape_markup(analysis::precursor_order(ci95.at(0).get<double>(), ci95.at(1).get<double>())),
        fmt::arg("u", unit));
  } else {
    text = "No precursor found: the analysis did not locate both maxima.";
  }
  if (analysis.value("accepted", false))
    text += " The curve passed the acceptance rules.";
  else
    text += " Analysis rejected: " +
            io::escape_markup(analysis.value("rejection", std::string("no reason given"))) + ".";
  if (analysis["mechanism"].is_object())
    text += " Breaking mechanism: <strong>" + mechanism_text(analysis["mechanism"]) + "</strong>.";
  return "<p class=\"summary\">" + text + "</p>\n";
}

std::string analysis_section(const json& analysis) {
  if (analysis.is_null()) return {};
  std::vector<std::vector<std::string>> rows{
      measured_row("x_p", "precursor strain: maximum of the energy rate ℰ = dE_e/dx", analysis["x_p"]),
      measured_row("ℰ_max", "energy-rate maximum", analysis["Erate_max"]),
      measured_row("x_c", "critical strain: force maximum", analysis["x_c"]),
      measured_row("F_c", "force maximum", analysis["F_c"]),
      measured_row("x_m", "strain of the elastic-energy maximum", analysis["x_m"]),
      measured_row("E_max", "elastic-energy maximum", analysis["E_max"]),
      measured_row(
          "δ_x",
          "delay x_c − x_p (method: " +
              io::escape_markup(analysis["delta_x"].is_object() ? analysis["delta_x"].value("method", "")
                                                                : std::string()) +
              ") ± sd",
          analysis["delta_x"]),
      measured_row("δ_x (direct)", "x_c − x_p from the two peak fits", analysis["delta_x_direct"]),
      measured_row("Γ", "(x_m − x_c)/δ_x (paper eq. 17)", analysis["Gamma"]),
      measured_row("A_r", "E_max/(x_p ℰ_max)", analysis["A_r"])};
  std::string html =
      "<h2>Analysis</h2>\n<p>From <code>analysis.json</code>; uncertainties are one standard "
      "deviation: for x<sub>p</sub>, x<sub>c</sub> and δ<sub>x</sub> the bootstrap's scaled as their 68 % "
      "intervals are (half that interval's width where it is symmetric), for the others, δ<sub>x</sub> "
      "(direct) among them, the bootstrap's own.</p>\n";
  html +=
      table({"quantity", "meaning", "value", "uncertainty", "unit"}, rows, {false, false, true, true, false});
  if (const auto& delta = analysis["delta_x"]; delta.is_object()) {
    const std::string unit = io::escape_markup(delta.value("unit", ""));
    const auto interval = [&](const char* key) {
      return fmt::format("[{}, {}]", number_text(delta.at(key).at(0).get<double>()),
                         number_text(delta.at(key).at(1).get<double>()));
    };
    html +=
        "<p>Distribution of δ<sub>x</sub> (bootstrap replicates, or the posterior of the shift-l1 "
        "method)" +
        uncalibrated_because(analysis) + ":</p>\n";
    html += table({"mode / estimate", "mean", "median", "sd", "68 % interval", "95 % interval", "unit"},
                  {{number_text(delta["map"].get<double>()), number_text(delta["mean"].get<double>()),
                    number_text(delta["median"].get<double>()), number_text(delta["sd"].get<double>()),
                    interval("ci68"), interval("ci95"), unit}},
                  {true, true, true, true, true, true, false});
  }
  if (const auto& alpha = analysis["alpha"]; alpha.is_object()) {
    const auto& value = alpha["from_delta_over_x_p"];
    const auto flag = [](const json& v) { return v.is_boolean() ? (v.get<bool>() ? "yes" : "no") : "–"; };
    html += "<p>Fiber-bundle comparison (power law p(x) = (1+α) x<sup>α</sup>):</p>\n";
    // analysis.json writes α as a plain number (null when δ_x/x_p implies none).
    const auto& range = alpha["ci68"];
    const std::string interval =
        range.is_array() && range.size() == 2 && (range[0].is_number() || range[1].is_number())
            ? "[" + number_or_dash(range[0]) + ", " + number_or_dash(range[1]) + "]"
            : "–";
    html +=
        table({"α from δ_x/x_p (eq. 18)", "α from δ_x's 68 % interval", "Γ within the FBM band 0 ≤ α ≤ 5",
               "A_r within the FBM band"},
              {{number_or_dash(value), interval, flag(alpha["Gamma_in_band"]), flag(alpha["A_r_in_band"])}});
  }
  if (const auto& mechanism = analysis["mechanism"]; mechanism.is_object()) {
    html += "<p>Breaking mechanism: <strong>" + mechanism_text(mechanism) + "</strong> — " +
            io::escape_markup(mechanism.value("reason", "")) + "</p>\n";
  }
  return html;
}

std::string run_section(const json& run) {
  if (run.is_null()) return "<h2>Run</h2>\n<p>No <code>run.json</code> in this folder.</p>\n";
  const auto get = [&](const char* key) { return run.contains(key) ? run[key] : json(); };
  const auto num = [&](const json& v) {
    return v.is_number() ? number_text(v.get<double>()) : io::escape_markup(v.dump());
  };
  const auto& balance = run["energy_balance"];
  const auto& plan = run["plan"];
  std::vector<std::vector<std::string>> rows{
      {"status", io::escape_markup(get("status").is_string() ? get("status").get<std::string>() : "unknown"),
       ""},
      {"why it stopped",
       io::escape_markup(get("stop_reason").is_string() ? get("stop_reason").get<std::string>() : "–"), ""},
      {"steps", num(get("steps")), "1"},
      {"final strain", value_text(get("final_strain")), unit_text(get("final_strain"))},
      {"bonds broken", num(get("broken_bonds")), "1"},
      {"wall time", value_text(get("wall_time")), unit_text(get("wall_time"))},
      {"throughput", value_text(get("throughput")), unit_text(get("throughput"))},
      {"threads", num(get("threads")), "1"}};
  const auto quantity_row = [&](const char* fact, const json& q) {
    rows.push_back({fact, value_text(q), unit_text(q)});
  };
  if (balance.is_object()) {
    rows.push_back(
        {"energy-balance drift, max |W − Σ E| / W",
         balance.contains("max_error_relative_to_work") ? num(balance["max_error_relative_to_work"]) : "–",
         "1"});
    quantity_row("energy-balance drift, max |W − Σ E|", balance.value("max_abs_error", json()));
    quantity_row("plate work W", balance.value("plate_work", json()));
  }
  if (plan.is_object()) {
    quantity_row("time step dt", plan.value("dt", json()));
    quantity_row("stability limit of dt", plan.value("critical_dt", json()));
  }
  if (run.contains("error")) rows.push_back({"error", io::escape_markup(run["error"].dump()), ""});
  std::string html = "<h2>Run</h2>\n<p>From <code>run.json</code>: <code>" +
                     io::escape_markup(run.value("command", std::string("?"))) + "</code></p>\n";
  html += table({"fact", "value", "unit"}, rows, {false, true, false});
  if (run["sample"].is_object()) html += "<h3>Sample</h3>\n" + key_value_table(run["sample"]);
  if (run["config"].is_object()) {
    html +=
        "<h2>Configuration</h2>\n<p>Every key resolved, as the run used it (meanings: <code>rupture run "
        "--help-config</code>).</p>\n" +
        key_value_table(run["config"], loading::config_key_unit);
  }
  return html;
}

// What the on-line monitor said during the run (run.json's "monitor"): when it warned, whether that
// was before the force maximum, and whether its prediction of x_c held.
std::string monitor_section(const json& run) {
  if (run.is_null()) return {};
  std::string html = "<h2>On-line monitor</h2>\n";
  const auto& monitor = run["monitor"];
  if (!monitor.is_object()) return html + "<p>Off in this run (<code>monitor.enabled = false</code>).</p>\n";
  const auto& warning = monitor["warning"];
  if (!warning.is_object()) {
    return html + fmt::format(
                      "<p class=\"summary\">The monitor never warned ({} rows seen): it did not confirm an "
                      "energy-rate maximum while the force still rose.</p>\n",
                      number_or_dash(monitor["samples"]));
  }
  const std::string strain_unit = unit_text(warning["strain"]);
  const auto& lead = monitor["lead"];
  std::string outcome =
      "the force maximum was not seen afterwards, so whether the warning came in time is unknown";
  if (is_quantity(lead) && lead["value"].is_number()) {
    const double by = lead["value"].get<double>();
    outcome = by > 0.0 ? fmt::format("<strong>before</strong> the force maximum, by {} {}", number_text(by),
                                     strain_unit)
                       : fmt::format("<strong>after</strong> the force maximum, by {} {} (too late)",
                                     number_text(-by), strain_unit);
  }
  html += fmt::format("<p class=\"summary\">The monitor warned at strain {} {}, {}.</p>\n",
                      value_text(warning["strain"]), strain_unit, outcome);
  const auto interval = [&](const json& q) {
    const json& v = is_quantity(q) ? q["value"] : json();
    return v.is_array() && v.size() == 2 ? "[" + number_or_dash(v[0]) + ", " + number_or_dash(v[1]) + "]"
                                         : std::string("–");
  };
  const auto yes_no = [](const json& v) { return v.is_boolean() ? (v.get<bool>() ? "yes" : "no") : "–"; };
  std::vector<std::vector<std::string>> rows{
      {"warning strain", value_text(warning["strain"]), strain_unit},
      {"x_p as the monitor saw it", value_text(warning["x_p"]), strain_unit},
      {"predicted x_c (interval)", interval(warning["x_c_predicted"]), strain_unit},
      {"x_c observed afterwards", value_text(monitor["x_c_observed"]), strain_unit},
      {"lead x_c − warning strain", value_text(lead), strain_unit},
      {"x_c inside the predicted interval", yes_no(monitor["x_c_held"]), ""},
      {"rows close enough to warn before the earliest predicted x_c", yes_no(warning["in_time"]), ""},
      {"largest row spacing that would have warned in time",
       value_text(warning["max_row_spacing_for_a_timely_warning"]), strain_unit}};
  return html + table({"fact", "value", "unit"}, rows, {false, true, false});
}

// The paper's claims checked against a scan (scan/claims), as the report's table.
std::string claims_section(const scan::Claims& claims) {
  std::vector<std::vector<std::string>> rows;
  for (const auto& claim : claims.rows)
    rows.push_back({io::escape_markup(claim.paper), io::escape_markup(claim.here)});
  return "<h2>The paper's claims against this scan</h2>\n<p>" + io::escape_markup(claims.counts()) +
         " Only accepted points count below (docs/study.md explains each claim).</p>\n" +
         table({"claim (paper, section 5)", "this scan"}, rows);
}

// results.csv as a table: the columns named in `wanted` (all when empty), numbers to 4 digits.
std::string results_table(const scan::ResultsTable& results, const std::vector<std::string>& wanted = {}) {
  std::vector<std::size_t> columns;
  if (wanted.empty()) {
    for (std::size_t c = 0; c < results.header.size(); ++c) columns.push_back(c);
  } else {
    for (const auto& name : wanted) columns.push_back(results.require(name));
  }
  std::vector<std::string> header;
  std::vector<bool> numeric;
  for (const std::size_t c : columns) {
    header.push_back(io::escape_markup(results.header[c]));
    numeric.push_back(results.header[c].find('[') != std::string::npos);  // a unit: a number column
  }
  std::vector<std::vector<std::string>> rows;
  for (std::size_t r = 0; r < results.rows.size(); ++r) {
    std::vector<std::string> cells;
    for (std::size_t k = 0; k < columns.size(); ++k) {
      const std::string& field = results.rows[r][columns[k]];
      cells.push_back(numeric[k] && !field.empty()
                          ? number_text(*results.number(r, results.header[columns[k]]))
                          : io::escape_markup(field));
    }
    rows.push_back(std::move(cells));
  }
  return table(header, rows, numeric);
}

json read_json_if_present(const fs::path& file) { return fs::exists(file) ? read_json(file) : json(); }

std::string run_report(const fs::path& folder, const std::string& command, std::size_t& count) {
  const json analysis = read_json_if_present(folder / "analysis.json");
  const json run = read_json_if_present(folder / "run.json");
  const auto drawn = figures::plot(folder, folder / "figures", {});
  std::string body = "<h1>Tension test: " + io::escape_markup(folder_name(folder)) + "</h1>\n";
  body += provenance(folder, command) + run_summary(analysis);
  body += figures_section(drawn, folder, count) + analysis_section(analysis) + monitor_section(run) +
          run_section(run);
  return page("rupture report: " + folder_name(folder), body);
}

std::string scan_report(const fs::path& folder, const std::string& command, std::size_t& count) {
  const auto drawn = figures::plot(folder, folder / "figures", {});
  const auto results = scan::read_results(folder / "results.csv");
  std::string body = "<h1>Parameter scan: " + io::escape_markup(folder_name(folder)) + "</h1>\n";
  body += provenance(folder, command);
  const auto claims = scan::check_claims(results);
  body += fmt::format(
      "<p class=\"summary\">{} points in <code>results.csv</code>, {} separated and accepted by the "
      "analysis (figures 16 and 17 show those).</p>\n",
      claims.points, claims.accepted);
  body += figures_section(drawn, folder, count) + claims_section(claims);
  if (fs::exists(folder / "scan.json")) {
    json scan = read_json(folder / "scan.json");
    scan.erase("points");  // one entry per point: the results table below says it better
    // The scan config is echoed as its TOML reads (units: `rupture scan --help-config`); the rest of
    // the bare numbers are counts.
    const auto unit_of = [](const std::string& key) { return key.starts_with("scan_config.") ? "" : "1"; };
    body +=
        "<h2>Scan</h2>\n<p>From <code>scan.json</code> (units of the scan config: <code>rupture scan "
        "--help-config</code>).</p>\n" +
        key_value_table(scan, unit_of);
  }
  body +=
      "<h2>Results</h2>\n<p>Every point of <code>results.csv</code> (units in brackets; empty: not found or "
      "not run; _err and _sd are one standard deviation; numbers to 4 digits, the file has them all).</p>\n" +
      results_table(results);
  return page("rupture scan report: " + folder_name(folder), body);
}

// A study folder (`rupture study`): the run config it wrote and the run beside it.
bool is_study_folder(const fs::path& folder) {
  return fs::exists(folder / "study.toml") && fs::exists(folder / "run" / "curves.csv");
}

// The study on one page: the run's loading curves and, beside them, δ_x against x_c of the scan
// (the paper's result); then the run's other figures, the scan's figures 15 and 17, the claims, and
// the numbers. Every figure is drawn now from the files of run/ and scan/.
std::string study_report(const fs::path& folder, const std::string& command, std::size_t& count) {
  const fs::path run_folder = folder / "run", scan_folder = folder / "scan";
  const json analysis = read_json_if_present(run_folder / "analysis.json");
  const json run = read_json_if_present(run_folder / "run.json");
  const auto run_drawn = figures::plot(run_folder, run_folder / "figures", {});
  const bool have_scan = figures::is_scan_folder(scan_folder);
  const auto scan_drawn =
      have_scan ? figures::plot(scan_folder, scan_folder / "figures", {}) : std::vector<figures::Drawn>{};
  std::vector<figures::Drawn> first, rest;
  for (const auto& f : run_drawn) (f.name == "loading" ? first : rest).push_back(f);
  for (const auto& f : scan_drawn) (f.name == "delay_vs_critical" ? first : rest).push_back(f);
  // results.csv read once, for the summary, the claims and the table.
  std::optional<scan::ResultsTable> results;
  std::optional<scan::Claims> claims;
  if (have_scan) {
    results = scan::read_results(scan_folder / "results.csv");
    claims = scan::check_claims(*results);
  }

  std::string body = "<h1>Study: " + io::escape_markup(folder_name(folder)) + "</h1>\n";
  body += provenance(folder, command) + run_summary(analysis);
  if (have_scan) {
    body += fmt::format(
        "<p class=\"summary\">The scan of the same tissue (<code>scan/</code>): {} points, {} accepted; "
        "{}.</p>\n",
        claims->points, claims->accepted, io::escape_markup(claims->rows.front().here));
  } else {
    body += "<p>No scan in this study (<code>--no-scan</code>): figures 15-17 need one.</p>\n";
  }
  body += figures_section(first, folder, count, "The run's loading curves and the scan's delay", true);
  body += figures_section(rest, folder, count, "More figures");
  if (have_scan) body += claims_section(*claims);
  body += "<h2>The run</h2>\n" + analysis_section(analysis) + monitor_section(run);
  if (have_scan) {
    body +=
        "<h2>The scan's points</h2>\n<p>From <code>scan/results.csv</code> (every column there; "
        "<code>rupture report scan</code> shows them all).</p>\n" +
        results_table(*results, {"k_n", "b_d", "status", "steps", "x_c", "x_p", "delta_x", "delta_x_lo95",
                                 "delta_x_hi95", "A_r", "alpha", "class", "accepted", "why", "wall_time"});
  }
  body += run_section(run);
  return page("rupture study report: " + folder_name(folder), body);
}

}  // namespace

ReportResult write_report(const fs::path& folder, const std::string& command) {
  if (!fs::is_directory(folder)) {
    throw InputError(
        folder.string(), "not a folder",
        "give a run folder (rupture run), a scan folder (rupture scan) or a study folder (rupture study)");
  }
  const io::FolderLock lock(folder, command);  // one writer: a run still writing it refuses the report
  ReportResult result;
  result.html = folder / "report.html";
  const std::string html = is_study_folder(folder)           ? study_report(folder, command, result.figures)
                           : figures::is_scan_folder(folder) ? scan_report(folder, command, result.figures)
                                                             : run_report(folder, command, result.figures);
  io::write_file_atomically(result.html, html);
  return result;
}

}  // namespace rupture::report
