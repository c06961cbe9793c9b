#include "core/progress.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdlib>

namespace rupture {

Progress::Mode Progress::output_mode() {
  const char* ci = std::getenv("CI");
  if (ci != nullptr && *ci != '\0') return Mode::quiet;
  return isatty(fileno(stderr)) != 0 ? Mode::terminal : Mode::batch;
}

Progress::Progress(std::string label, double total, const std::filesystem::path& log,
                   std::chrono::milliseconds line_interval)
    : label_(std::move(label)),
      total_(total),
      mode_(output_mode()),
      line_interval_(line_interval),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_),
      last_line_(start_) {
  // A log that cannot be opened costs the log, not the run.
  if (!log.empty()) log_.reset(std::fopen(log.c_str(), "a"));
  active_ = mode_ != Mode::quiet || log_ != nullptr;
}

Progress::~Progress() {
  if (drawn_) std::fprintf(stderr, "\r\033[K");
}

bool Progress::due() {
  const auto now = std::chrono::steady_clock::now();
  redraw_ = mode_ == Mode::terminal && now - last_draw_ >= std::chrono::milliseconds(250);
  line_ = (mode_ == Mode::batch || log_ != nullptr) && now - last_line_ >= line_interval_;
  if (redraw_) last_draw_ = now;
  if (line_) last_line_ = now;
  return redraw_ || line_;
}

void Progress::update(double done, const std::string& detail) {
  if (active_ && due()) emit(done, detail, false);
}

std::string Progress::line(double done, const std::string& detail) const {
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double rate = elapsed > 0 ? done / elapsed : 0.0;
  std::string text = fmt::format("{}: {:.0f}", label_, done);
  if (total_ > 0) text += fmt::format("/{:.0f} ({:.1f} %)", total_, 100.0 * done / total_);
  text += fmt::format(", {:.3g}/s, {:.0f} s elapsed", rate, elapsed);
  if (total_ > 0 && rate > 0 && done < total_) text += fmt::format(", ETA {:.0f} s", (total_ - done) / rate);
  if (!detail.empty()) text += ", " + detail;
  return text;
}

void Progress::emit(double done, const std::string& detail, bool last) {
  const std::string text = line(done, detail);
  if (redraw_ && !last) {
    std::fprintf(stderr, "\r\033[K%s", text.c_str());
    std::fflush(stderr);
    drawn_ = true;
  }
  if (line_ && mode_ == Mode::batch && !last) {
    std::fprintf(stderr, "%s\n", text.c_str());
    std::fflush(stderr);
  }
  if ((line_ || last) && log_) {
    std::fprintf(log_.get(), "%s%s\n", text.c_str(), last ? " (end)" : "");
    std::fflush(log_.get());
  }
}

void Progress::finish(double done, const std::string& detail) {
  if (drawn_) {
    std::fprintf(stderr, "\r\033[K");
    std::fflush(stderr);
    drawn_ = false;
  }
  if (log_ && done >= 0.0) {
    redraw_ = line_ = false;
    emit(done, detail, true);
  }
  log_.reset();
}

}  // namespace rupture
