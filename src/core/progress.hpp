// core/progress: how long work reports itself. On a terminal, one status line redrawn a few times a
// second; in a batch job (stderr not a terminal, CI unset) one full line per minute on stderr, so a
// scheduler's log shows the run moving; with CI set, nothing on stderr. With a log file, the same line
// is appended to it every minute and once at the end, whatever stderr is (a run's run.log).
#pragma once

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

namespace rupture {

class Progress {
 public:
  enum class Mode { terminal, batch, quiet };

  // `total` is the amount of work in the caller's unit (steps, runs, ...); 0 means unknown. `log`
  // (optional) is appended to; `line_interval` is the pace of batch and log lines.
  explicit Progress(std::string label, double total = 0.0, const std::filesystem::path& log = {},
                    std::chrono::milliseconds line_interval = std::chrono::minutes(1));
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  // Reports `done` units finished; `detail` is appended (e.g. "strain 1.23 %, 412 broken").
  // Cheap when called often: it only formats when a line is due.
  void update(double done, const std::string& detail = {});
  // Same, but builds the detail only when a line is due.
  template <class DetailFn>
  void update_with(double done, DetailFn&& detail) {
    if (active_ && due()) emit(done, detail(), false);
  }
  // Clears the terminal line; the log gets a last line with `done` and `detail`.
  void finish(double done = -1.0, const std::string& detail = {});

  Mode mode() const { return mode_; }
  static Mode output_mode();  // from stderr and CI
  static bool terminal_output() { return output_mode() == Mode::terminal; }

 private:
  bool due();
  std::string line(double done, const std::string& detail) const;
  void emit(double done, const std::string& detail, bool last);

  std::string label_;
  double total_;
  Mode mode_;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> log_{nullptr, &std::fclose};
  std::chrono::milliseconds line_interval_;
  bool active_;                         // anything to report to
  bool drawn_ = false;                  // a terminal line is on screen
  bool redraw_ = false, line_ = false;  // what the pending emit() writes
  std::chrono::steady_clock::time_point start_, last_draw_, last_line_;
};

}  // namespace rupture
