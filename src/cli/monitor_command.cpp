// cli/monitor_command: `rupture monitor [FILE]` — feeds a loading curve row by row (stdin, a file,
// or with --follow a file that is still being written, e.g. the curves.csv of a running
// `rupture run`) to analysis::Monitor, prints the precursor warning the moment it is confirmed,
// and at the end the lead and whether the prediction held.
#include <charconv>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "analysis/analysis.hpp"
#include "analysis/monitor.hpp"
#include "cli/analyze_command.hpp"
#include "cli/commands.hpp"
#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "rupture/version.hpp"

namespace rupture::cli {

namespace {

struct MonitorCommandOptions {
  std::string file = "-", json;
  bool follow = false;
  double idle_timeout = 10.0;  // s without new data before a followed file counts as finished
  int poll_ms = 200;           // ms between reads of a followed file
  analysis::ColumnChoice columns;
  analysis::MonitorOptions monitor;
};

// Reads a CSV incrementally: comment lines and the header first, then one row at a time.
class RowReader {
 public:
  RowReader(const MonitorCommandOptions& o) : options_(o), source_(o.file == "-" ? "stdin" : o.file) {
    if (o.file == "-") {
      file_ = stdin;
    } else {
      file_ = std::fopen(o.file.c_str(), "rb");
      if (!file_) throw InputError(o.file, "cannot open the file", "check the path");
    }
  }
  ~RowReader() {
    if (file_ && file_ != stdin) std::fclose(file_);
  }
  RowReader(const RowReader&) = delete;
  RowReader& operator=(const RowReader&) = delete;

  // The next complete line (without '\n'), or false at the end of the input.
  bool next_line(std::string& line) {
    auto last_data = std::chrono::steady_clock::now();
    for (;;) {
      const auto eol = buffer_.find('\n', start_);
      if (eol != std::string::npos) {
        line.assign(buffer_, start_, eol - start_);
        start_ = eol + 1;
        ++line_number_;
        return true;
      }
      buffer_.erase(0, start_);
      start_ = 0;
      char chunk[65536];
      const std::size_t got = std::fread(chunk, 1, sizeof chunk, file_);
      if (got > 0) {
        buffer_.append(chunk, got);
        last_data = std::chrono::steady_clock::now();
        continue;
      }
      const double idle = std::chrono::duration<double>(std::chrono::steady_clock::now() - last_data).count();
      if (!options_.follow || file_ == stdin || idle >= options_.idle_timeout) {
        if (buffer_.empty()) return false;
        line.swap(buffer_);  // a last line without '\n'
        buffer_.clear();
        ++line_number_;
        return true;
      }
      std::clearerr(file_);
      std::this_thread::sleep_for(std::chrono::milliseconds(options_.poll_ms));
    }
  }

  std::size_t line_number() const { return line_number_; }
  const std::string& source() const { return source_; }

 private:
  const MonitorCommandOptions& options_;
  std::string source_;
  std::FILE* file_ = nullptr;
  std::string buffer_;
  std::size_t start_ = 0, line_number_ = 0;
};

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

// The value of field `column` of a data row, with the file's line and column in any error.
double field(std::string_view line, std::size_t column, std::size_t expected_fields, const io::CsvTable& header,
             const RowReader& reader) {
  std::size_t start = 0, index = 0, fields = 1;
  std::string_view wanted;
  for (std::size_t i = 0; i <= line.size(); ++i) {
    if (i == line.size() || line[i] == ',') {
      if (index == column) wanted = trim(line.substr(start, i - start));
      ++index;
      start = i + 1;
      if (i < line.size()) ++fields;
    }
  }
  const auto where = fmt::format("{}:{}", reader.source(), reader.line_number());
  if (fields != expected_fields) {
    throw InputError(where, fmt::format("{} fields where the header has {}", fields, expected_fields),
                     "every row needs one value per header column");
  }
  if (!wanted.empty() && wanted.front() == '+') wanted.remove_prefix(1);
  double value = 0.0;
  const auto result = std::from_chars(wanted.data(), wanted.data() + wanted.size(), value);
  if (wanted.empty() || result.ec != std::errc() || result.ptr != wanted.data() + wanted.size() || !std::isfinite(value)) {
    throw InputError(where, fmt::format("column {} ('{}'): '{}' is not a number", column + 1, header.header[column], wanted),
                     "use plain decimal numbers such as 1.5e-3");
  }
  return value;
}

std::string interval(const analysis::Interval& i) { return fmt::format("[{:.6g}, {:.6g}]", i.low, i.high); }

}  // namespace

void add_monitor_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<MonitorCommandOptions>();
  auto* cmd = app.add_subcommand("monitor", "Watch a loading curve as it grows and warn when failure is imminent");
  cmd->add_option("file", o->file, "CSV loading curve, '-' for stdin (default)");
  cmd->add_flag("--follow", o->follow, "Keep reading a file that is still being written until it stays idle for --idle-timeout");
  cmd->add_option("--idle-timeout", o->idle_timeout, "Seconds without new rows after which a followed file is finished")
      ->check(CLI::Range(0.0, 1e6));
  cmd->add_option("--poll", o->poll_ms, "Milliseconds between reads of a followed file")->check(CLI::Range(1, 60000));
  cmd->add_option("--json", o->json, "Also write the warning and the outcome to this JSON file");
  add_curve_column_options(*cmd, o->columns);
  cmd->add_option("--window", o->monitor.window, "Samples in each causal cubic fit")->check(CLI::Range(7, 100000));
  cmd->add_option("--drop", o->monitor.drop, "Fraction by which the energy rate must fall below its maximum")
      ->check(CLI::Range(0.001, 0.9));
  cmd->add_option("--confirm", o->monitor.confirm, "Consecutive samples below that level that confirm the maximum")
      ->check(CLI::Range(1, 100000));
  cmd->callback([o, &exit_code] {
    RowReader reader(*o);
    std::string line, header_text;
    while (reader.next_line(line)) {
      const auto t = trim(line);
      if (t.empty() || t.front() == '#') continue;
      header_text = std::string(t);
      break;
    }
    if (header_text.empty()) throw InputError(reader.source(), "no header line", "the first non-comment line must name the columns");
    const auto header = io::parse_csv(header_text, reader.source());
    const auto columns = analysis::find_curve_columns(header, o->columns);
    const std::size_t fields = header.header.size();
    analysis::Monitor monitor(o->monitor);
    while (reader.next_line(line)) {
      const auto t = trim(line);
      if (t.empty() || t.front() == '#') continue;
      const double x = o->columns.strain_scale * field(t, columns.strain, fields, header, reader);
      const double f = o->columns.force_scale * field(t, columns.force, fields, header, reader);
      const double e = o->columns.energy_scale * field(t, columns.energy, fields, header, reader);
      if (const auto w = monitor.add_point(x, f, e)) {
        fmt::print("WARNING at strain {:.6g} {}: energy-rate maximum passed (x_p = {:.6g} ± {:.2g} {}) while the force "
                   "still rises; predicted x_c in {} {}, E_max in {} {} (FBM, 0 <= alpha <= 5)\n",
                   w->strain, columns.strain_unit, w->x_p, w->x_p_error, columns.strain_unit, interval(w->x_c),
                   columns.strain_unit, interval(w->E_max), columns.energy_unit);
        if (!w->in_time) {
          fmt::print("the rows are too far apart to warn in time: this warning comes after the earliest predicted x_c; "
                     "rows at most {:.3g} {} apart would have warned before it\n",
                     w->max_row_spacing, columns.strain_unit);
        }
        std::fflush(stdout);
      }
    }
    const auto s = monitor.summary();
    fmt::print("{} samples read from {}\n", s.samples, reader.source());
    if (!s.warning) {
      fmt::print("no warning: {}\n", s.force_peaked_before_warning ? "the force peaked before an energy-rate maximum was confirmed"
                                                                   : "no energy-rate maximum was confirmed");
    }
    if (s.x_c) fmt::print("observed x_c = {:.6g} {}\n", *s.x_c, columns.strain_unit);
    if (s.lead) {
      fmt::print("lead x_c - x_warning = {:.6g} {}; x_c prediction {}\n", *s.lead, columns.strain_unit,
                 *s.x_c_held ? "held" : "missed");
    }
    if (s.E_max_held) fmt::print("observed E_max = {:.6g} {}; E_max prediction {}\n", *s.E_max, columns.energy_unit, *s.E_max_held ? "held" : "missed");
    if (!o->json.empty()) {
      nlohmann::json j = {{"tool", "rupture monitor"}, {"version", version_string},
                          {"inputs", {{"file", o->file}, {"window", o->monitor.window}, {"drop", o->monitor.drop},
                                      {"confirm", o->monitor.confirm}, {"alpha_range", {o->monitor.alpha_low, o->monitor.alpha_high}}}},
                          {"units", {{"strain", columns.strain_unit}, {"force", columns.force_unit}, {"energy", columns.energy_unit}}}};
      j.update(analysis::to_json(s));
      io::write_json_atomically(o->json, j);
    }
    (void)exit_code;
  });
}

}  // namespace rupture::cli
