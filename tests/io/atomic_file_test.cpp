#include "io/atomic_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "support/tool.hpp"

namespace rupture::io {
namespace {

namespace fs = std::filesystem;
using rupture::testing::TempDir;

TEST(AtomicFile, CommitReplacesTargetAndLeavesNoTemporary) {
  TempDir tmp;
  const auto& dir = tmp.path();
  write_file_atomically(dir / "a.txt", "old\n");
  write_file_atomically(dir / "a.txt", "new\n");
  EXPECT_EQ(read_text_file(dir / "a.txt"), "new\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

TEST(AtomicFile, AbandonedWriteKeepsThePreviousVersion) {
  TempDir tmp;
  const auto& dir = tmp.path();
  write_file_atomically(dir / "a.txt", "kept\n");
  {
    AtomicFile file(dir / "a.txt");
    file.write("half-writ");
    // no commit: as if an exception unwound the writer
  }
  EXPECT_EQ(read_text_file(dir / "a.txt"), "kept\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

TEST(AtomicFile, UnwritableFolderIsAClearError) {
  EXPECT_THROW(AtomicFile("/nonexistent/folder/x.txt"), RunError);
}

TEST(AtomicFile, JsonIsPrettyAndTerminated) {
  TempDir tmp;
  const auto& dir = tmp.path();
  write_json_atomically(dir / "r.json", nlohmann::json{{"x_c", 0.5}});
  const auto text = read_text_file(dir / "r.json");
  EXPECT_EQ(nlohmann::json::parse(text)["x_c"], 0.5);
  EXPECT_EQ(text.back(), '\n');
}

}  // namespace
}  // namespace rupture::io
