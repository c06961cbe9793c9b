#include "io/atomic_file.hpp"

#include <filesystem>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/error.hpp"

namespace rupture::io {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
  auto dir = fs::temp_directory_path() / ("rupture_test_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(AtomicFile, CommitReplacesTargetAndLeavesNoTemporary) {
  const auto dir = fresh_dir("atomic");
  write_file_atomically(dir / "a.txt", "old\n");
  write_file_atomically(dir / "a.txt", "new\n");
  EXPECT_EQ(read_text_file(dir / "a.txt"), "new\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
  fs::remove_all(dir);
}

TEST(AtomicFile, AbandonedWriteKeepsThePreviousVersion) {
  const auto dir = fresh_dir("abandon");
  write_file_atomically(dir / "a.txt", "kept\n");
  {
    AtomicFile file(dir / "a.txt");
    file.write("half-writ");
    // no commit: as if an exception unwound the writer
  }
  EXPECT_EQ(read_text_file(dir / "a.txt"), "kept\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
  fs::remove_all(dir);
}

TEST(AtomicFile, UnwritableFolderIsAClearError) {
  EXPECT_THROW(AtomicFile("/nonexistent/folder/x.txt"), RunError);
}

TEST(AtomicFile, JsonIsPrettyAndTerminated) {
  const auto dir = fresh_dir("json");
  write_json_atomically(dir / "r.json", nlohmann::json{{"x_c", 0.5}});
  const auto text = read_text_file(dir / "r.json");
  EXPECT_EQ(nlohmann::json::parse(text)["x_c"], 0.5);
  EXPECT_EQ(text.back(), '\n');
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rupture::io
