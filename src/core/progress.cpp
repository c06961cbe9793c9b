#include "core/progress.hpp"

#include <cstdio>
#include <cstdlib>
#include <unistd.h>

#include <fmt/format.h>

namespace rupture {

bool Progress::terminal_output() {
  const char* ci = std::getenv("CI");
  if (ci != nullptr && *ci != '\0') return false;
  return isatty(fileno(stderr)) != 0;
}

Progress::Progress(std::string label, double total)
    : label_(std::move(label)),
      total_(total),
      enabled_(terminal_output()),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

Progress::~Progress() { finish(); }

bool Progress::redraw_due() {
  const auto now = std::chrono::steady_clock::now();
  if (now - last_draw_ < std::chrono::milliseconds(250)) return false;
  last_draw_ = now;
  return true;
}

void Progress::update(double done, const std::string& detail) {
  if (enabled_ && redraw_due()) draw(done, detail);
}

void Progress::draw(double done, const std::string& detail) {
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double rate = elapsed > 0 ? done / elapsed : 0.0;
  std::string line = fmt::format("{}: {:.0f}", label_, done);
  if (total_ > 0) {
    line += fmt::format("/{:.0f} ({:.1f} %)", total_, 100.0 * done / total_);
  }
  line += fmt::format(", {:.3g}/s", rate);
  if (total_ > 0 && rate > 0 && done < total_) {
    const double eta = (total_ - done) / rate;
    line += fmt::format(", ETA {:.0f} s", eta);
  }
  if (!detail.empty()) line += ", " + detail;
  std::fprintf(stderr, "\r\033[K%s", line.c_str());
  std::fflush(stderr);
  drawn_ = true;
}

void Progress::finish() {
  if (enabled_ && drawn_) {
    std::fprintf(stderr, "\r\033[K");
    std::fflush(stderr);
    drawn_ = false;
  }
}

}  // namespace rupture
