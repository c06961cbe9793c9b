// core/progress: one status line for long work, redrawn on a terminal at most a few times a second;
// silent when stderr is not a terminal or CI is set, so pipes and logs stay clean.
#pragma once

#include <chrono>
#include <string>

namespace rupture {

class Progress {
 public:
  // `total` is the amount of work in the caller's unit (steps, runs, ...); 0 means unknown.
  explicit Progress(std::string label, double total = 0.0);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  // Reports `done` units finished; `detail` is appended (e.g. "strain 1.23 %, 412 broken").
  // Cheap when called often: it only formats when a redraw is due.
  void update(double done, const std::string& detail = {});
  // Same, but builds the detail only when a redraw is due.
  template <class DetailFn>
  void update_with(double done, DetailFn&& detail) {
    if (enabled_ && redraw_due()) draw(done, detail());
  }
  void finish();

  bool enabled() const { return enabled_; }
  static bool terminal_output();

 private:
  bool redraw_due();
  void draw(double done, const std::string& detail);

  std::string label_;
  double total_;
  bool enabled_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_, last_draw_;
};

}  // namespace rupture
