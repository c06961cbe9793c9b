// core/progress: the log file gets a line at the pace asked for and one at the end, with the count,
// the rate and the caller's detail; the terminal mode follows stderr and CI.
#include "core/progress.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "support/tool.hpp"

namespace rupture {
namespace {

using ::testing::HasSubstr;

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

TEST(Progress, LogGetsPeriodicLinesAndAnEndLine) {
  testing::TempDir dir;
  const auto log = dir / "work.log";
  {
    Progress progress("work", 100.0, log, std::chrono::milliseconds(20));
    for (int k = 1; k <= 5; ++k) {
      std::this_thread::sleep_for(std::chrono::milliseconds(30));
      progress.update_with(20.0 * k, [&] { return "step " + std::to_string(k); });
    }
    progress.finish(100.0, "all done");
  }
  const auto lines = lines_of(testing::slurp(log));
  ASSERT_GE(lines.size(), 3u) << testing::slurp(log);  // periodic lines, then the end line
  EXPECT_THAT(lines.front(), HasSubstr("work: 20/100 (20.0 %)"));
  EXPECT_THAT(lines.front(), HasSubstr("step 1"));
  EXPECT_THAT(lines.back(), HasSubstr("work: 100/100 (100.0 %)"));
  EXPECT_THAT(lines.back(), HasSubstr("all done (end)"));
}

TEST(Progress, CiSilencesStderrButNotTheLog) {
  const char* before = std::getenv("CI");
  const std::string saved = before != nullptr ? before : "";
  ::setenv("CI", "1", 1);
  EXPECT_EQ(Progress::output_mode(), Progress::Mode::quiet);
  testing::TempDir dir;
  {
    Progress progress("quiet", 0.0, dir / "quiet.log", std::chrono::milliseconds(0));
    progress.update(1.0);
    progress.finish(1.0);
  }
  EXPECT_EQ(lines_of(testing::slurp(dir / "quiet.log")).size(), 2u);  // one update line, the end line
  ::unsetenv("CI");
  EXPECT_EQ(Progress::output_mode(),
            isatty(fileno(stderr)) ? Progress::Mode::terminal : Progress::Mode::batch);
  if (before != nullptr) ::setenv("CI", saved.c_str(), 1);
}

}  // namespace
}  // namespace rupture
