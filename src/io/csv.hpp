// io/csv: numeric CSV tables, the exchange format of loading curves.
// Convention (docs/formats.md): optional leading '#' comment lines, one header line whose fields are
// `name[unit]` (the unit in brackets is optional), then rows of numbers separated by commas.
// Also read, as researchers' other tools write them: columns separated by spaces or tabs (when the
// header has no comma), the header as the last '#' line before the numbers (LAMMPS fix ave/time
// and fix print, Yade saveDataTxt), pandas' unnamed index column (named "index"), and a UTF-8 byte
// order mark. Two columns of one name are refused.
// Every reader error names the file, line and column and says what to do.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rupture::io {

struct CsvTable {
  std::string source;                        // file name used in messages
  std::vector<std::string> comments;         // '#' lines before the header, without the '#'
  std::vector<std::string> header;           // full field names, e.g. "strain[%]"
  std::vector<std::vector<double>> columns;  // columns[c][row]
  std::vector<std::size_t> line_of_row;      // 1-based line number of each row in the source

  std::size_t rows() const { return columns.empty() ? 0 : columns.front().size(); }
  // Index of the column called `name`, matched against the whole field or the part before '['.
  std::optional<std::size_t> find(std::string_view name) const;
  // Like find(), but throws InputError listing the available columns.
  std::size_t require(std::string_view name) const;
  const std::vector<double>& column(std::string_view name) const { return columns[require(name)]; }
};

// The part of a header field before '[' (trimmed), and the unit inside the brackets ("" if none).
std::string column_name(std::string_view field);
std::string column_unit(std::string_view field);

// The reader behind parse_csv, fed one line at a time (without its '\n'), so that a file still
// being written can be read as it grows (rupture monitor --follow). Every error as parse_csv's.
class CsvLineReader {
 public:
  explicit CsvLineReader(std::string source);
  // True when the line was a data row: its values are then in row().
  bool add_line(std::string_view line);
  const std::vector<double>& row() const { return row_; }
  bool has_header() const { return have_header_; }
  // The source, comments and header (no rows); throws InputError when no header came yet.
  const CsvTable& header() const;
  std::size_t line_number() const { return line_number_; }

 private:
  void set_header(std::string_view line, std::size_t number);
  bool all_numbers(std::string_view line);
  CsvTable table_;
  std::vector<std::string_view> fields_;
  std::vector<double> row_;
  std::size_t line_number_ = 0, last_comment_line_ = 0;
  std::uint64_t bytes_read_ = 0;  // before the current line, for a NUL byte's position
  bool have_header_ = false, comma_separated_ = true;
};

CsvTable parse_csv(std::string_view text, const std::string& source);
CsvTable read_csv(const std::filesystem::path& path);

// Formats one row with the shortest representation that reads back to the same double, so files
// are byte-identical whenever the numbers are.
std::string format_csv_row(const std::vector<double>& values);
std::string format_csv_header(const std::vector<std::string>& fields);

}  // namespace rupture::io
