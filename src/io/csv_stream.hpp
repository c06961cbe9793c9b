// io/csv_stream: a CSV file written row by row while a run goes on (it cannot be atomic), flushed
// after every row so that a killed run keeps everything recorded so far, with the byte count and
// hash of what is on disk for a checkpoint to record. A resume checks that the file still begins
// with that prefix, then cuts it back and appends. Not: the rows' meaning (loading/run).
#pragma once

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/hash.hpp"

namespace rupture::io {

// The first `bytes` of a file and their FNV-1a 64.
struct FilePrefix {
  std::uint64_t bytes = 0;
  std::uint64_t hash = Fnv1a{}.hash;
};

// Why `path` does not begin with `prefix` (missing, shorter, other content), or nullopt when it
// does. With check_hash false only the length is compared (checkpoints of rupture 0.1).
std::optional<std::string> prefix_mismatch(const std::filesystem::path& path, const FilePrefix& prefix,
                                           bool check_hash = true);

class CsvStream {
 public:
  // A new file with its header and no comment lines (so that any CSV reader takes it as it is).
  CsvStream(const std::filesystem::path& path, const std::vector<std::string>& header);
  // The file of an earlier run, cut back to `prefix` (the caller checked it with prefix_mismatch)
  // and appended to.
  CsvStream(const std::filesystem::path& path, const FilePrefix& prefix);

  void row(const std::vector<double>& values);
  void flush();
  // Flushed and on disk (fsync): what a checkpoint may record.
  FilePrefix sync();

 private:
  void put(const std::string& text);
  [[noreturn]] void fail() const;
  std::filesystem::path path_;
  std::unique_ptr<std::FILE, decltype(&std::fclose)> file_;
  FilePrefix written_;
};

}  // namespace rupture::io
