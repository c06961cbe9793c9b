// cli/monitor_command: `rupture monitor [FILE]` — feeds a loading curve row by row (stdin, a file,
// or with --follow a file that is still being written, e.g. the curves.csv of a running
// `rupture run`) to analysis::Monitor, prints the precursor warning the moment it is confirmed,
// and at the end the lead and whether the prediction held.
#include <fmt/format.h>
#include <sys/stat.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "analysis/analysis.hpp"
#include "analysis/monitor.hpp"
#include "cli/analyze_command.hpp"
#include "cli/commands.hpp"
#include "core/error.hpp"
#include "io/csv.hpp"
#include "rupture/version.hpp"

namespace rupture::cli {

namespace {

struct MonitorCommandOptions {
  std::string file = "-";
  bool json = false;
  bool follow = false;
  double idle_timeout = 10.0;  // s without new data before a followed file counts as finished
  int poll_ms = 200;           // ms between reads of a followed file
  analysis::ColumnChoice columns;
  analysis::MonitorOptions monitor;
};

// The lines of a file or stdin as they arrive. Following a file, it waits for more, and notices
// when the file is cut shorter than what was read (truncated and rewritten) or another file takes
// its name (replaced): the curve then starts over.
class LineSource {
 public:
  enum class Got { line, end, restarted };

  explicit LineSource(const MonitorCommandOptions& o)
      : options_(o), source_(o.file == "-" ? "stdin" : o.file) {
    if (o.file == "-")
      file_ = stdin;
    else
      open();
  }
  ~LineSource() {
    if (file_ && file_ != stdin) std::fclose(file_);
  }
  LineSource(const LineSource&) = delete;
  LineSource& operator=(const LineSource&) = delete;

  // The next complete line (without '\n'); `restarted` when a followed file changed under us.
  Got next(std::string& line) {
    auto last_data = std::chrono::steady_clock::now();
    for (;;) {
      const auto eol = buffer_.find('\n', start_);
      if (eol != std::string::npos) {
        line.assign(buffer_, start_, eol - start_);
        start_ = eol + 1;
        return Got::line;
      }
      buffer_.erase(0, start_);
      start_ = 0;
      char chunk[65536];
      const std::size_t got = std::fread(chunk, 1, sizeof chunk, file_);
      if (got > 0) {
        buffer_.append(chunk, got);
        offset_ += got;
        last_data = std::chrono::steady_clock::now();
        continue;
      }
      const double idle = std::chrono::duration<double>(std::chrono::steady_clock::now() - last_data).count();
      if (!options_.follow || file_ == stdin || idle >= options_.idle_timeout) {
        if (buffer_.empty()) return Got::end;
        line.swap(buffer_);  // a last line without '\n'
        buffer_.clear();
        return Got::line;
      }
      if (const char* change = changed()) {
        std::fclose(file_);
        open();
        buffer_.clear();
        start_ = offset_ = 0;
        fmt::print("{}: the file was {}; reading it again from the start\n", source_, change);
        return Got::restarted;
      }
      std::clearerr(file_);
      std::this_thread::sleep_for(std::chrono::milliseconds(options_.poll_ms));
    }
  }

  const std::string& source() const { return source_; }

 private:
  void open() {
    file_ = std::fopen(options_.file.c_str(), "rb");
    if (!file_) throw InputError(options_.file, "cannot open the file", "check the path");
  }
  // "truncated", "replaced" or nullptr.
  const char* changed() const {
    struct stat open_file {
    }, named{};
    if (::fstat(fileno(file_), &open_file) != 0) return nullptr;
    if (::stat(options_.file.c_str(), &named) != 0) return nullptr;  // gone for now: keep waiting
    if (named.st_ino != open_file.st_ino || named.st_dev != open_file.st_dev) return "replaced";
    if (std::uint64_t(open_file.st_size) < offset_) return "truncated";
    return nullptr;
  }

  const MonitorCommandOptions& options_;
  std::string source_;
  std::FILE* file_ = nullptr;
  std::string buffer_;
  std::size_t start_ = 0;
  std::uint64_t offset_ = 0;  // bytes read from the open file
};

std::string interval(const analysis::Interval& i) { return fmt::format("[{:.6g}, {:.6g}]", i.low, i.high); }

}  // namespace

// The live warning: on stdout, or on stderr when --json keeps stdout for the document.
void print_warning(const analysis::Warning& warning, const analysis::CurveColumns& columns, bool json) {
  std::FILE* live = json ? stderr : stdout;  // --json keeps stdout for the document
  fmt::print(live,
             "WARNING at strain {:.6g} {}: energy-rate maximum passed (x_p = {:.6g} ± {:.2g} {}) while the "
             "force "
             "still rises; predicted x_c in {} {}, E_max in {} {} (FBM, 0 <= alpha <= 5)\n",
             warning.strain, columns.strain_unit, warning.x_p, warning.x_p_error, columns.strain_unit,
             interval(warning.x_c), columns.strain_unit, interval(warning.E_max), columns.energy_unit);
  if (!warning.in_time) {
    fmt::print(live,
               "the rows are too far apart to warn in time: this warning comes after the earliest predicted "
               "x_c; "
               "rows at most {:.3g} {} apart would have warned before it\n",
               warning.max_row_spacing, columns.strain_unit);
  }
  std::fflush(live);
}

// The outcome at the end: one JSON document, or lines of text.
void print_outcome(const MonitorCommandOptions& options, const analysis::Monitor& monitor,
                   const analysis::CurveColumns& columns, const std::string& source) {
  const auto s = monitor.summary();
  if (options.json) {
    nlohmann::json j = {{"tool", "rupture monitor"},
                        {"version", version_string},
                        {"inputs",
                         {{"file", options.file},
                          {"window", options.monitor.window},
                          {"drop", options.monitor.drop},
                          {"confirm", options.monitor.confirm},
                          {"alpha_range", {options.monitor.alpha_low, options.monitor.alpha_high}}}}};
    j.update(analysis::to_json(s, columns.strain_unit, columns.energy_unit));
    fmt::print("{}\n", j.dump(2));
    return;
  }
  fmt::print("{} samples read from {}\n", s.samples, source);
  if (!s.warning) {
    fmt::print("no warning: {}\n", s.force_peaked_before_warning
                                       ? "the force peaked before an energy-rate maximum was confirmed"
                                       : "no energy-rate maximum was confirmed");
  }
  if (s.x_c) fmt::print("observed x_c = {:.6g} {}\n", *s.x_c, columns.strain_unit);
  if (s.lead) {
    fmt::print("lead x_c - x_warning = {:.6g} {}; x_c prediction {}\n", *s.lead, columns.strain_unit,
               *s.x_c_held ? "held" : "missed");
  }
  if (s.E_max_held)
    fmt::print("observed E_max = {:.6g} {}; E_max prediction {}\n", *s.E_max, columns.energy_unit,
               *s.E_max_held ? "held" : "missed");
}

void add_monitor_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<MonitorCommandOptions>();
  auto* cmd =
      app.add_subcommand("monitor", "Watch a loading curve as it grows and warn when failure is imminent");
  cmd->add_option("file", o->file, "CSV loading curve, '-' for stdin (default)");
  cmd->add_flag("--follow", o->follow,
                "Keep reading a file that is still being written until it stays idle for --idle-timeout");
  cmd->add_option("--idle-timeout", o->idle_timeout,
                  "Seconds without new rows after which a followed file is finished")
      ->check(CLI::Range(0.0, 1e6));
  cmd->add_option("--poll", o->poll_ms, "Milliseconds between reads of a followed file")
      ->check(CLI::Range(1, 60000));
  cmd->add_flag(
      "--json", o->json,
      "Print the warning and the outcome as one JSON document at the end (the live warning goes to stderr)");
  add_curve_column_options(*cmd, o->columns);
  cmd->add_option("--window", o->monitor.window, "Samples in each causal cubic fit")
      ->check(CLI::Range(7, 100000));
  cmd->add_option("--drop", o->monitor.drop, "Fraction by which the energy rate must fall below its maximum")
      ->check(CLI::Range(0.001, 0.9));
  cmd->add_option("--confirm", o->monitor.confirm,
                  "Consecutive samples below that level that confirm the maximum")
      ->check(CLI::Range(1, 100000));
  cmd->callback([o, &exit_code] {
    LineSource input(*o);
    std::optional<io::CsvLineReader> csv(std::in_place, input.source());
    std::optional<analysis::Monitor> monitor(std::in_place, o->monitor);
    std::optional<analysis::CurveColumns> columns;
    std::string line;
    for (auto got = input.next(line); got != LineSource::Got::end; got = input.next(line)) {
      if (got == LineSource::Got::restarted) {
        csv.emplace(input.source());
        monitor.emplace(o->monitor);
        columns.reset();
        continue;
      }
      if (!csv->add_line(line)) continue;
      if (!columns) columns = analysis::find_curve_columns(csv->header(), o->columns);
      const auto& row = csv->row();
      const double x = o->columns.strain_scale * row[columns->strain];
      const double f = o->columns.force_scale * row[columns->force];
      const double e = o->columns.energy_scale * row[columns->energy];
      if (const auto w = monitor->add_point(x, f, e)) {
        print_warning(*w, *columns, o->json);
      }
    }
    if (!columns) columns = analysis::find_curve_columns(csv->header(), o->columns);  // a header, no rows
    print_outcome(*o, *monitor, *columns, input.source());
    (void)exit_code;
  });
}

}  // namespace rupture::cli
