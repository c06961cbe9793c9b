// io/atomic_file: files that appear whole or not at all. Content goes to a temporary file beside
// the target, is flushed and fsync'ed, then renamed over the target, so a crash, a kill or a full
// disk never leaves a half-written output and never destroys the previous version.
#pragma once

#include <cstdio>
#include <filesystem>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <string_view>

namespace rupture::io {

class AtomicFile {
 public:
  // Opens a temporary file next to `target`; throws RunError naming the folder if it cannot.
  explicit AtomicFile(std::filesystem::path target);
  ~AtomicFile();  // discards the temporary file unless commit() succeeded
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  void write(std::string_view text);
  std::FILE* handle() { return file_; }  // for fmt::print(handle(), ...)
  // Flush, fsync and rename over the target; throws RunError (e.g. disk full) and leaves the
  // target untouched on failure.
  void commit();

  const std::filesystem::path& target() const { return target_; }

 private:
  std::filesystem::path target_, temporary_;
  std::FILE* file_ = nullptr;
  bool committed_ = false;
};

void write_file_atomically(const std::filesystem::path& target, std::string_view content);
// Pretty-printed JSON (2-space indent, trailing newline), written atomically.
void write_json_atomically(const std::filesystem::path& target, const nlohmann::json& document);

// "PATH: write failed (reason); what to do", for a write that failed with `error` (errno): a full
// disk, or the file size limit (EFBIG, `ulimit -f`; SIGXFSZ is ignored so that it arrives here).
std::string write_failure(const std::filesystem::path& path, int error);

// Reads a whole file; throws InputError naming the file when it cannot be read.
std::string read_text_file(const std::filesystem::path& path);

// Throws InputError naming `source` and the line when `text` holds a NUL byte: a binary or damaged
// file, which a parser would otherwise read only up to that byte (a TOML file's later keys lost).
void require_text(std::string_view text, const std::string& source);

}  // namespace rupture::io
