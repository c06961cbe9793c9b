// io/atomic_file: files that appear whole or not at all. Content goes to a temporary file beside
// the target, is flushed and fsync'ed, then renamed over the target, so a crash, a kill or a full
// disk never leaves a half-written output and never destroys the previous version.
#pragma once

#include <cstdint>
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

// The command-line convention for outputs: "-" is standard output, anything else a file written
// atomically as above.
void write_output(const std::filesystem::path& target, std::string_view content);

// "PATH: write failed (reason); what to do", for a write that failed with `error` (errno): a full
// disk, or the file size limit (EFBIG, `ulimit -f`; SIGXFSZ is ignored so that it arrives here).
std::string write_failure(const std::filesystem::path& path, int error);

// The largest file a reader takes unless it says otherwise, and the largest config (TOML) file:
// a device such as /dev/zero, or the wrong file, is refused instead of exhausting memory.
inline constexpr std::uint64_t max_file_bytes = std::uint64_t(8) << 30;
inline constexpr std::uint64_t max_config_bytes = std::uint64_t(16) << 20;

// Reads a whole file of at most `max_bytes`; throws InputError naming the file when it cannot be
// read or is larger.
std::string read_file(const std::filesystem::path& path, std::uint64_t max_bytes = max_file_bytes);
// The same for a text file, which must hold no NUL byte (require_text): a binary file is refused
// at its first NUL, before the rest of it is read.
std::string read_text_file(const std::filesystem::path& path, std::uint64_t max_bytes = max_file_bytes);

// Throws InputError naming `source` and the line when `text` holds a NUL byte: a binary or damaged
// file, which a parser would otherwise read only up to that byte (a TOML file's later keys lost).
// `text` may be a piece of a larger file that starts at line `first_line`, after `bytes_before` bytes.
void require_text(std::string_view text, const std::string& source, std::size_t first_line = 1,
                  std::uint64_t bytes_before = 0);

}  // namespace rupture::io
