// tests/support/tool: helpers shared by the test suites: run the built `rupture` binary and capture
// its exit code and output; make a fresh temporary folder per test.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

namespace rupture::testing {

struct ToolResult {
  int exit_code = -1;
  std::string out;  // stdout
  std::string err;  // stderr
};

// A folder under the system temp dir named after the running test, emptied on creation and removed
// when the object goes out of scope (kept if the test failed, for inspection).
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = std::string(info->test_suite_name()) + "_" + info->name();
    for (auto& ch : name)
      if (ch == '/') ch = '_';
    path_ = std::filesystem::temp_directory_path() / ("rupture_" + name + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    if (!::testing::Test::HasFailure()) {
      std::error_code ignored;
      std::filesystem::remove_all(path_, ignored);
    }
  }
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

inline std::string slurp(const std::filesystem::path& file) {
  std::string text;
  if (std::FILE* f = std::fopen(file.c_str(), "rb")) {
    std::array<char, 65536> buffer;
    std::size_t n;
    while ((n = std::fread(buffer.data(), 1, buffer.size(), f)) > 0) text.append(buffer.data(), n);
    std::fclose(f);
  }
  return text;
}

// A path as one shell word (the test folders hold no single quotes).
inline std::string shell_quoted(const std::filesystem::path& path) { return "'" + path.string() + "'"; }

// Runs `rupture <args>` through the shell (args are shell words: quote paths yourself), with
// stdin from /dev/null unless `stdin_file` is given, and CI=1 so no progress line is drawn.
inline ToolResult run_rupture(const std::string& args, const std::string& stdin_file = "/dev/null") {
  const auto dir = std::filesystem::temp_directory_path();
  const auto stem = "rupture_tool_" + std::to_string(::getpid()) + "_" +
                    std::to_string(reinterpret_cast<std::uintptr_t>(&args));
  const auto out = dir / (stem + ".out"), err = dir / (stem + ".err");
  const std::string command = "CI=1 '" + std::string(RUPTURE_BINARY) + "' " + args + " <'" + stdin_file +
                              "' >'" + out.string() + "' 2>'" + err.string() + "'";
  const int status = std::system(command.c_str());
  ToolResult result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.out = slurp(out);
  result.err = slurp(err);
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return result;
}

}  // namespace rupture::testing
