#include "io/csv.hpp"

#include <fmt/format.h>

#include "core/error.hpp"
#include "core/tokens.hpp"
#include "io/atomic_file.hpp"

namespace rupture::io {

namespace {

using tokens::trim;

// Splits one line into `fields` (views into `line`): on commas, or on runs of blanks.
void split_fields(std::string_view line, bool comma_separated, std::vector<std::string_view>& fields) {
  if (comma_separated)
    tokens::split_commas(line, fields);
  else
    tokens::split_words(line, fields);
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

CsvLineReader::CsvLineReader(std::string source) { table_.source = std::move(source); }

void CsvLineReader::set_header(std::string_view line, std::size_t number) {
  comma_separated_ = line.find(',') != std::string_view::npos;
  split_fields(line, comma_separated_, fields_);
  for (std::size_t c = 0; c < fields_.size(); ++c) {
    std::string name(fields_[c]);
    // pandas' to_csv() writes its index as a first column with an empty name.
    if (name.empty() && c == 0 && fields_.size() > 1) name = "index";
    if (name.empty())
      throw InputError(fmt::format("{}:{}", table_.source, number), "empty column name in the header",
                       "give every column a name, e.g. strain[%],force[N]");
    for (std::size_t d = 0; d < table_.header.size(); ++d)
      if (column_name(table_.header[d]) == column_name(name))
        throw InputError(
            fmt::format("{}:{}", table_.source, number),
            fmt::format("columns {} and {} are both called '{}'", d + 1, c + 1, excerpt(column_name(name))),
            "give every column its own name");
    table_.header.push_back(std::move(name));
  }
  table_.columns.resize(table_.header.size());
  have_header_ = true;
}

bool CsvLineReader::all_numbers(std::string_view line) {
  split_fields(line, line.find(',') != std::string_view::npos, fields_);
  for (auto f : fields_)
    if (!tokens::number<double>(f)) return false;
  return !fields_.empty();
}

bool CsvLineReader::add_line(std::string_view text) {
  ++line_number_;
  require_text(text, table_.source, line_number_, bytes_read_);
  bytes_read_ += text.size() + 1;
  if (line_number_ == 1 && text.substr(0, 3) == "\xEF\xBB\xBF")
    text.remove_prefix(3);  // a UTF-8 byte order mark
  const std::string_view line = trim(text);
  if (line.empty()) return false;
  if (line.front() == '#') {
    if (!have_header_) {
      table_.comments.emplace_back(trim(line.substr(1)));
      last_comment_line_ = line_number_;
    }
    return false;
  }
  if (!have_header_) {
    // LAMMPS (fix ave/time, fix print) and Yade (saveDataTxt) name the columns in the last '#'
    // line before the numbers.
    if (all_numbers(line) && last_comment_line_ > 0) {
      const std::string names = table_.comments.back();
      table_.comments.pop_back();
      set_header(names, last_comment_line_);
    } else {
      set_header(line, line_number_);
      return false;
    }
  }
  split_fields(line, comma_separated_, fields_);
  const auto where = [&] { return fmt::format("{}:{}", table_.source, line_number_); };
  if (fields_.size() != table_.header.size())
    throw InputError(where(),
                     fmt::format("{} fields where the header has {}", fields_.size(), table_.header.size()),
                     "every row needs one value per header column");
  row_.resize(fields_.size());
  for (std::size_t c = 0; c < fields_.size(); ++c) {
    const auto value = tokens::number<double>(fields_[c]);
    if (!value)
      throw InputError(where(),
                       fmt::format("column {} ('{}'): '{}' is not a number", c + 1, excerpt(table_.header[c]),
                                   excerpt(fields_[c])),
                       "use plain decimal numbers such as 1.5e-3");
    row_[c] = *value;
  }
  return true;
}

const CsvTable& CsvLineReader::header() const {
  if (!have_header_)
    throw InputError(table_.source, "no header line", "the first non-comment line must name the columns");
  return table_;
}

CsvTable parse_csv(std::string_view text, const std::string& source) {
  CsvLineReader reader(source);
  CsvTable table;
  for (std::size_t pos = 0; pos < text.size();) {
    std::size_t eol = text.find('\n', pos);
    if (eol == std::string_view::npos) eol = text.size();
    if (reader.add_line(text.substr(pos, eol - pos))) {
      if (table.columns.empty()) table.columns.resize(reader.row().size());
      for (std::size_t c = 0; c < reader.row().size(); ++c) table.columns[c].push_back(reader.row()[c]);
      table.line_of_row.push_back(reader.line_number());
    }
    pos = eol + 1;
  }
  const CsvTable& header = reader.header();
  table.source = header.source;
  table.comments = header.comments;
  table.header = header.header;
  table.columns.resize(table.header.size());
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
