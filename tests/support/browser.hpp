// tests/support/browser: headless Chromium on a report page — a screenshot, or the DOM after the load
// event (where the report records data-figures="N of M loaded"), with the page's console messages.
#pragma once

#include <fmt/format.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "support/tool.hpp"

namespace rupture::testing {

struct BrowserRun {
  int exit_code = -1;
  std::string dom, log;
};

// Headless Chromium on a page: screenshot 1200 x 2000 into `screenshot` (if given) or the DOM after
// the load event on stdout, console messages on stderr (--enable-logging=stderr).
inline BrowserRun chromium(const std::filesystem::path& page, const std::filesystem::path& work,
                           const std::string& mode) {
  std::filesystem::create_directories(work / "profile");
  const std::string command = fmt::format(
      "timeout 120 chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run "
      "--disable-background-networking --disable-component-update --disable-sync --user-data-dir={} "
      "--enable-logging=stderr --v=0 --window-size=1200,2000 {} 'file://{}' >{} 2>{}",
      shell_quoted(work / "profile"), mode, std::filesystem::absolute(page).string(),
      shell_quoted(work / "stdout"), shell_quoted(work / "stderr"));
  BrowserRun run;
  const int status = std::system(command.c_str());
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.dom = slurp(work / "stdout");
  run.log = slurp(work / "stderr");
  return run;
}

// Lines of Chromium's log that come from the page: console messages and uncaught exceptions.
inline std::vector<std::string> console_lines(const std::string& log) {
  std::vector<std::string> lines;
  std::size_t at = 0;
  while (at < log.size()) {
    const auto end = std::min(log.find('\n', at), log.size());
    const std::string line = log.substr(at, end - at);
    if (line.find(":CONSOLE") != std::string::npos || line.find("Uncaught") != std::string::npos)
      lines.push_back(line);
    at = end + 1;
  }
  return lines;
}

inline bool have_chromium() { return std::system("command -v chromium >/dev/null 2>&1") == 0; }

}  // namespace rupture::testing
