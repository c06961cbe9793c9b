#include "io/csv_stream.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <fstream>

#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/csv.hpp"

namespace rupture::io {

std::optional<std::string> prefix_mismatch(const std::filesystem::path& path, const FilePrefix& prefix,
                                           bool check_hash) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) return fmt::format("cannot be read ({})", ec.message());
  if (size < prefix.bytes)
    return fmt::format("holds {} bytes, fewer than the {} its checkpoint recorded", size, prefix.bytes);
  if (!check_hash) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  Fnv1a hash;
  std::vector<char> buffer(1 << 16);
  for (std::uint64_t left = prefix.bytes; left > 0;) {
    const auto n = std::streamsize(std::min<std::uint64_t>(left, buffer.size()));
    if (!in.read(buffer.data(), n)) return std::string("cannot be read to the end of its recorded part");
    hash.add(buffer.data(), std::size_t(n));
    left -= std::uint64_t(n);
  }
  if (hash.hash != prefix.hash)
    return fmt::format("its first {} bytes are not those its checkpoint recorded (edited, or another run's?)",
                       prefix.bytes);
  return std::nullopt;
}

CsvStream::CsvStream(const std::filesystem::path& path, const std::vector<std::string>& header)
    : path_(path), file_(std::fopen(path.c_str(), "wb"), &std::fclose) {
  if (!file_) fail();
  put(format_csv_header(header));
  flush();
}

CsvStream::CsvStream(const std::filesystem::path& path, const FilePrefix& prefix)
    : path_(path), file_(nullptr, &std::fclose), written_(prefix) {
  std::error_code ec;
  std::filesystem::resize_file(path, prefix.bytes, ec);
  if (ec)
    throw RunError(
        fmt::format("{}: cannot cut back to {} bytes ({})", path.string(), prefix.bytes, ec.message()));
  file_.reset(std::fopen(path.c_str(), "ab"));
  if (!file_) fail();
}

void CsvStream::row(const std::vector<double>& values) { put(format_csv_row(values)); }

void CsvStream::flush() {
  if (std::fflush(file_.get()) != 0) fail();
}

FilePrefix CsvStream::sync() {
  flush();
  if (fsync(fileno(file_.get())) != 0) fail();
  return written_;
}

void CsvStream::put(const std::string& text) {
  if (std::fputs(text.c_str(), file_.get()) == EOF) fail();
  written_.bytes += text.size();
  Fnv1a hash{written_.hash};  // FNV-1a runs on from the hash of the bytes before
  hash.add(text);
  written_.hash = hash.hash;
}

void CsvStream::fail() const { throw RunError(write_failure(path_, errno)); }

}  // namespace rupture::io
