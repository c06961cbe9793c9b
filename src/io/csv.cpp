#include "io/csv.hpp"

#include <charconv>

#include <fmt/format.h>

#include "core/error.hpp"
#include "io/atomic_file.hpp"

namespace rupture::io {

namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

// Splits one line on commas into `fields` (views into `line`).
void split_fields(std::string_view line, std::vector<std::string_view>& fields) {
  fields.clear();
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = line.find(',', start);
    fields.push_back(trim(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
}

bool parse_double(std::string_view text, double& value) {
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  const auto* end = text.data() + text.size();
  const auto result = std::from_chars(text.data(), end, value);
  return result.ec == std::errc() && result.ptr == end && !text.empty();
}

}  // namespace

std::string column_name(std::string_view field) {
  const auto bracket = field.find('[');
  return std::string(trim(field.substr(0, bracket)));
}

std::string column_unit(std::string_view field) {
  const auto open = field.find('[');
  const auto close = field.rfind(']');
  if (open == std::string_view::npos || close == std::string_view::npos || close < open) return {};
  return std::string(trim(field.substr(open + 1, close - open - 1)));
}

std::optional<std::size_t> CsvTable::find(std::string_view name) const {
  for (std::size_t c = 0; c < header.size(); ++c) {
    if (header[c] == name || column_name(header[c]) == name) return c;
  }
  return std::nullopt;
}

std::size_t CsvTable::require(std::string_view name) const {
  if (auto c = find(name)) return *c;
  std::string available;
  for (const auto& h : header) available += (available.empty() ? "" : ", ") + h;
  throw InputError(source, fmt::format("no column '{}'", name),
                   fmt::format("the header has: {}", available.empty() ? "(nothing)" : available));
}

CsvTable parse_csv(std::string_view text, const std::string& source) {
  CsvTable table;
  table.source = source;
  std::vector<std::string_view> fields;
  std::size_t line_number = 0;
  std::size_t pos = 0;
  bool have_header = false;
  while (pos < text.size()) {
    std::size_t eol = text.find('\n', pos);
    if (eol == std::string_view::npos) eol = text.size();
    const std::string_view line = trim(text.substr(pos, eol - pos));
    pos = eol + 1;
    ++line_number;
    if (line.empty()) continue;
    if (line.front() == '#') {
      if (!have_header) table.comments.emplace_back(trim(line.substr(1)));
      continue;
    }
    split_fields(line, fields);
    if (!have_header) {
      for (auto f : fields) {
        if (f.empty()) {
          throw InputError(fmt::format("{}:{}", source, line_number), "empty column name in the header",
                           "give every column a name, e.g. strain[%],force[N]");
        }
        table.header.emplace_back(f);
      }
      table.columns.resize(table.header.size());
      have_header = true;
      continue;
    }
    if (fields.size() != table.header.size()) {
      throw InputError(fmt::format("{}:{}", source, line_number),
                       fmt::format("{} fields where the header has {}", fields.size(), table.header.size()),
                       "every row needs one value per header column");
    }
    for (std::size_t c = 0; c < fields.size(); ++c) {
      double value;
      if (!parse_double(fields[c], value)) {
        throw InputError(fmt::format("{}:{}", source, line_number),
                         fmt::format("column {} ('{}'): '{}' is not a number", c + 1, table.header[c], fields[c]),
                         "use plain decimal numbers such as 1.5e-3");
      }
      table.columns[c].push_back(value);
    }
    table.line_of_row.push_back(line_number);
  }
  if (!have_header) {
    throw InputError(source, "no header line", "the first non-comment line must name the columns");
  }
  return table;
}

CsvTable read_csv(const std::filesystem::path& path) { return parse_csv(read_text_file(path), path.string()); }

std::string format_csv_row(const std::vector<double>& values) {
  std::string row;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i) row += ',';
    fmt::format_to(std::back_inserter(row), "{}", values[i]);
  }
  row += '\n';
  return row;
}

std::string format_csv_header(const std::vector<std::string>& fields) {
  std::string row;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (i) row += ',';
    row += fields[i];
  }
  row += '\n';
  return row;
}

}  // namespace rupture::io
