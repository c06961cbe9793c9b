#include "io/csv.hpp"

#include <fmt/format.h>

#include <charconv>

#include "core/error.hpp"
#include "io/atomic_file.hpp"

namespace rupture::io {

namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

// Splits one line into `fields` (views into `line`): on commas, or on runs of spaces and tabs.
void split_fields(std::string_view line, bool comma_separated, std::vector<std::string_view>& fields) {
  fields.clear();
  if (comma_separated) {
    std::size_t start = 0;
    for (;;) {
      const std::size_t comma = line.find(',', start);
      fields.push_back(
          trim(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start)));
      if (comma == std::string_view::npos) break;
      start = comma + 1;
    }
    return;
  }
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) fields.push_back(line.substr(start, i - start));
  }
}

bool parse_double(std::string_view text, double& value) {
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  const auto* end = text.data() + text.size();
  const auto result = std::from_chars(text.data(), end, value);
  return result.ec == std::errc() && result.ptr == end && !text.empty();
}

// A message quotes at most 80 bytes of the input.
std::string capped(std::string_view text) {
  return text.size() <= 80 ? std::string(text) : std::string(text.substr(0, 77)) + "...";
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
  require_text(text, source);
  CsvTable table;
  table.source = source;
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);  // a UTF-8 byte order mark
  std::vector<std::string_view> fields;
  std::size_t line_number = 0, pos = 0;
  bool have_header = false, comma_separated = true;
  std::string_view last_comment;
  std::size_t last_comment_line = 0;
  const auto set_header = [&](std::string_view line, std::size_t number) {
    comma_separated = line.find(',') != std::string_view::npos;
    split_fields(line, comma_separated, fields);
    for (std::size_t c = 0; c < fields.size(); ++c) {
      std::string name(fields[c]);
      // pandas' to_csv() writes its index as a first column with an empty name.
      if (name.empty() && c == 0 && fields.size() > 1) name = "index";
      if (name.empty()) {
        throw InputError(fmt::format("{}:{}", source, number), "empty column name in the header",
                         "give every column a name, e.g. strain[%],force[N]");
      }
      for (std::size_t d = 0; d < table.header.size(); ++d) {
        if (column_name(table.header[d]) == column_name(name)) {
          throw InputError(
              fmt::format("{}:{}", source, number),
              fmt::format("columns {} and {} are both called '{}'", d + 1, c + 1, capped(column_name(name))),
              "give every column its own name");
        }
      }
      table.header.push_back(std::move(name));
    }
    table.columns.resize(table.header.size());
    have_header = true;
  };
  const auto all_numbers = [&](std::string_view line) {
    split_fields(line, line.find(',') != std::string_view::npos, fields);
    double value;
    for (auto f : fields) {
      if (!parse_double(f, value)) return false;
    }
    return !fields.empty();
  };
  while (pos < text.size()) {
    std::size_t eol = text.find('\n', pos);
    if (eol == std::string_view::npos) eol = text.size();
    const std::string_view line = trim(text.substr(pos, eol - pos));
    pos = eol + 1;
    ++line_number;
    if (line.empty()) continue;
    if (line.front() == '#') {
      if (!have_header) {
        table.comments.emplace_back(trim(line.substr(1)));
        last_comment = trim(line.substr(1));
        last_comment_line = line_number;
      }
      continue;
    }
    if (!have_header) {
      // LAMMPS (fix ave/time, fix print) and Yade (saveDataTxt) name the columns in the last
      // '#' line before the numbers.
      if (all_numbers(line) && !last_comment.empty()) {
        table.comments.pop_back();
        set_header(last_comment, last_comment_line);
      } else {
        set_header(line, line_number);
        continue;
      }
    }
    split_fields(line, comma_separated, fields);
    if (fields.size() != table.header.size()) {
      throw InputError(fmt::format("{}:{}", source, line_number),
                       fmt::format("{} fields where the header has {}", fields.size(), table.header.size()),
                       "every row needs one value per header column");
    }
    for (std::size_t c = 0; c < fields.size(); ++c) {
      double value;
      if (!parse_double(fields[c], value)) {
        throw InputError(fmt::format("{}:{}", source, line_number),
                         fmt::format("column {} ('{}'): '{}' is not a number", c + 1, capped(table.header[c]),
                                     capped(fields[c])),
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

CsvTable read_csv(const std::filesystem::path& path) {
  return parse_csv(read_text_file(path), path.string());
}

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
