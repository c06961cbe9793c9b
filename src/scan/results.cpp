#include "scan/results.hpp"

#include <fmt/format.h>

#include "core/error.hpp"
#include "core/tokens.hpp"
#include "io/atomic_file.hpp"
#include "io/csv.hpp"

namespace rupture::scan {

const std::vector<ResultColumn>& result_columns() {
  static const std::vector<ResultColumn> columns = {
      {"point", "1", true, "index of the point in the scan's order (grid first, then the list)"},
      {"k_n", "N/mm", true, "bond stiffness"},
      {"b_d", "mm", true, "bond breaking distance (a strain when the base config uses the relative rule)"},
      {"dt", "s", true, "time step used"},
      {"ramp_steps", "1", true, "steps of the loading-speed ramp"},
      {"max_strain", "%", true, "stop strain used"},
      {"status", "", true, "ok | no_separation | unstable | error (| running | pending while unfinished)"},
      {"stop_reason", "", true, "separated | max_strain | max_steps | unstable"},
      {"steps", "1", true, "steps run"},
      {"final_strain", "%", true, "strain when the run stopped"},
      {"broken_bonds", "1", true, "bonds broken when the run stopped"},
      {"x_c", "%", true, "critical strain (force maximum)"},
      {"x_c_err", "%", true, "its 1-sigma uncertainty (half its 68 % interval)"},
      {"F_c", "N", true, "force maximum"},
      {"F_c_err", "N", true, "its 1-sigma uncertainty"},
      {"x_p", "%", true, "precursor strain (maximum of the energy rate)"},
      {"x_p_err", "%", true, "its 1-sigma uncertainty (half its 68 % interval)"},
      {"Erate_max", "mJ/%", true, "maximum of the elastic energy rate dE_e/dx"},
      {"Erate_max_err", "mJ/%", true, "its 1-sigma uncertainty"},
      {"x_m", "%", true, "strain of the elastic energy maximum"},
      {"x_m_err", "%", true, "its 1-sigma uncertainty"},
      {"E_max", "mJ", true, "elastic energy maximum"},
      {"E_max_err", "mJ", true, "its 1-sigma uncertainty"},
      {"delta_x", "%", true, "delta_x = x_c - x_p of the fitted maxima (rupture analyze's default)"},
      {"delta_x_sd", "%", true, "its standard deviation (the bootstrap's, scaled as its 68 % interval)"},
      {"delta_x_map", "%", true, "the same estimate (a posterior maximum under --delay-method shift-l1)"},
      {"delta_x_lo68", "%", true, "68 % interval, lower end (scaled as docs/analysis.md, Calibration, says)"},
      {"delta_x_hi68", "%", true, "68 % interval, upper end"},
      {"delta_x_lo95", "%", true, "95 % interval, lower end"},
      {"delta_x_hi95", "%", true, "95 % interval, upper end"},
      {"Gamma", "1", true, "Gamma = (x_m - x_c) / delta_x, retardation of the energy maximum (eq. 17)"},
      {"Gamma_err", "1", true, "its 1-sigma uncertainty"},
      {"A_r", "1", true, "A_r = E_max / (Erate_max x_p), the energy ratio of figure 17"},
      {"A_r_err", "1", true, "its 1-sigma uncertainty"},
      {"alpha", "1", true, "FBM power-law exponent implied by delta_x / x_p (eq. 18)"},
      {"class", "", true, "breaking mechanism: brittle | hyper-elastic | semi-ductile | ductile"},
      {"accepted", "1", true, "1 when the curve passed the acceptance rules, else 0"},
      {"why", "", true, "why not accepted, or why the point failed"},
      {"wall_time", "s", false, "wall time of the run and its analysis"},
  };
  return columns;
}

namespace {

bool needs_quotes(std::string_view text) { return text.find_first_of(",\"\n\r") != std::string_view::npos; }

std::string field_text(const nlohmann::json& value) {
  if (value.is_null()) return {};
  if (value.is_boolean()) return value.get<bool>() ? "1" : "0";
  if (value.is_number_integer()) return fmt::format("{}", value.get<std::int64_t>());
  if (value.is_number_unsigned()) return fmt::format("{}", value.get<std::uint64_t>());
  if (value.is_number()) return fmt::format("{}", value.get<double>());
  const std::string text = value.is_string() ? value.get<std::string>() : value.dump();
  if (!needs_quotes(text)) return text;
  std::string quoted = "\"";
  for (char ch : text) {
    if (ch == '"') quoted += '"';
    quoted += ch;
  }
  return quoted + "\"";
}

// Splits one record starting at `pos` (RFC 4180: quoted fields may hold commas, "" and line breaks);
// advances `pos` past the record's line break.
std::vector<std::string> split_record(std::string_view text, std::size_t& pos, std::size_t& line,
                                      const std::string& source) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  const std::size_t first_line = line;
  while (pos < text.size()) {
    const char ch = text[pos++];
    if (quoted) {
      if (ch == '"' && pos < text.size() && text[pos] == '"') {
        fields.back() += '"';
        ++pos;
      } else if (ch == '"') {
        quoted = false;
      } else {
        if (ch == '\n') ++line;
        fields.back() += ch;
      }
    } else if (ch == '"' && fields.back().empty()) {
      quoted = true;
    } else if (ch == ',') {
      fields.emplace_back();
    } else if (ch == '\n') {
      ++line;
      break;
    } else if (ch != '\r') {
      fields.back() += ch;
    }
  }
  if (quoted)
    throw InputError(fmt::format("{}:{}", source, first_line), "a quoted field is never closed",
                     "end the field with a double quote");
  return fields;
}

}  // namespace

std::string format_results(const std::vector<nlohmann::json>& rows,
                           const std::vector<std::string>& comments) {
  std::string out;
  for (const auto& c : comments) out += "# " + c + "\n";
  std::vector<std::string> header;
  for (const auto& column : result_columns()) header.push_back(column.header());
  out += io::format_csv_header(header);
  for (const auto& row : rows) {
    bool first = true;
    for (const auto& column : result_columns()) {
      if (!first) out += ',';
      first = false;
      const auto it = row.find(column.name);
      if (it != row.end()) out += field_text(*it);
    }
    out += '\n';
  }
  return out;
}

std::size_t ResultsTable::require(std::string_view name) const {
  for (std::size_t c = 0; c < header.size(); ++c)
    if (header[c] == name || io::column_name(header[c]) == name) return c;
  std::string available;
  for (const auto& h : header) available += (available.empty() ? "" : ", ") + h;
  throw InputError(source, fmt::format("no column '{}'", name), "the header has: " + available);
}

std::optional<double> ResultsTable::number(std::size_t row, std::string_view name) const {
  const std::size_t c = require(name);
  const std::string& field = rows.at(row)[c];
  if (field.empty()) return std::nullopt;
  const auto value = tokens::number<double>(field);
  if (!value)
    throw InputError(fmt::format("{}: row {}", source, row + 1),
                     fmt::format("column '{}': '{}' is not a number", header[c], field),
                     "numeric columns hold plain numbers or nothing");
  return *value;
}

ResultsTable parse_results(std::string_view text, const std::string& source) {
  ResultsTable table;
  table.source = source;
  std::size_t pos = 0, line = 1;
  while (pos < text.size()) {
    const std::size_t record_line = line;
    if (text[pos] == '#' && table.header.empty()) {
      const std::size_t eol = std::min(text.find('\n', pos), text.size());
      std::string_view comment = text.substr(pos + 1, eol - pos - 1);
      if (!comment.empty() && comment.front() == ' ') comment.remove_prefix(1);
      table.comments.emplace_back(comment);
      pos = eol + 1;
      ++line;
      continue;
    }
    auto fields = split_record(text, pos, line, source);
    if (fields.size() == 1 && fields.front().empty()) continue;  // blank line
    if (table.header.empty()) {
      table.header = std::move(fields);
      continue;
    }
    if (fields.size() != table.header.size())
      throw InputError(fmt::format("{}:{}", source, record_line),
                       fmt::format("{} fields where the header has {}", fields.size(), table.header.size()),
                       "every row needs one field per header column (empty for a missing value)");
    table.rows.push_back(std::move(fields));
  }
  if (table.header.empty())
    throw InputError(source, "no header line", "the first non-comment line names the columns");
  return table;
}

ResultsTable read_results(const std::filesystem::path& path) {
  return parse_results(io::read_text_file(path), path.string());
}

std::vector<PointOutcome> read_outcomes(const ResultsTable& table) {
  std::vector<PointOutcome> points;
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    const auto k_n = table.number(r, "k_n"), b_d = table.number(r, "b_d");
    if (!k_n || !b_d) continue;
    PointOutcome p;
    p.k_n = *k_n;
    p.b_d = *b_d;
    p.status = table.text(r, "status");
    p.mechanism = table.text(r, "class");
    p.why = table.text(r, "why");
    p.accepted = table.number(r, "accepted").value_or(0.0) == 1.0;
    p.x_c = table.number(r, "x_c");
    p.x_c_err = table.number(r, "x_c_err");
    p.delta_x = table.number(r, "delta_x");
    p.delta_lo68 = table.number(r, "delta_x_lo68");
    p.delta_hi68 = table.number(r, "delta_x_hi68");
    p.delta_lo95 = table.number(r, "delta_x_lo95");
    p.alpha = table.number(r, "alpha");
    p.A_r = table.number(r, "A_r");
    p.A_r_err = table.number(r, "A_r_err");
    p.gamma = table.number(r, "Gamma");
    points.push_back(std::move(p));
  }
  return points;
}

}  // namespace rupture::scan
