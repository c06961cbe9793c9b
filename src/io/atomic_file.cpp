#include "io/atomic_file.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <memory>
#include <nlohmann/json.hpp>

#include "core/error.hpp"

namespace rupture::io {

namespace fs = std::filesystem;

AtomicFile::AtomicFile(fs::path target) : target_(std::move(target)) {
  temporary_ = target_;
  temporary_ += fmt::format(".tmp-{}", static_cast<long>(getpid()));
  file_ = std::fopen(temporary_.c_str(), "wb");
  if (file_ == nullptr) {
    throw RunError(fmt::format("{}: cannot create file ({}); check that the folder exists and is writable",
                               target_.string(), std::strerror(errno)));
  }
}

AtomicFile::~AtomicFile() {
  if (file_ != nullptr) std::fclose(file_);
  if (!committed_) {
    std::error_code ignored;
    fs::remove(temporary_, ignored);
  }
}

void AtomicFile::write(std::string_view text) {
  if (!text.empty() && std::fwrite(text.data(), 1, text.size(), file_) != text.size()) {
    throw RunError(write_failure(target_, errno));
  }
}

void AtomicFile::commit() {
  const bool flushed = std::fflush(file_) == 0 && fsync(fileno(file_)) == 0;
  const int error = errno;
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  if (!flushed || !closed) {
    throw RunError(write_failure(target_, error) + "; the previous file is kept");
  }
  std::error_code ec;
  fs::rename(temporary_, target_, ec);
  if (ec) throw RunError(fmt::format("{}: cannot replace file ({})", target_.string(), ec.message()));
  committed_ = true;
}

std::string write_failure(const fs::path& path, int error) {
  const char* hint =
      error == EFBIG ? "the file size limit is reached (ulimit -f); raise it" : "is the disk full?";
  return fmt::format("{}: write failed ({}); {}", path.string(), std::strerror(error), hint);
}

void write_file_atomically(const fs::path& target, std::string_view content) {
  AtomicFile file(target);
  file.write(content);
  file.commit();
}

void write_json_atomically(const fs::path& target, const nlohmann::json& document) {
  write_file_atomically(target, document.dump(2) + "\n");
}

namespace {

std::string read_whole(const fs::path& path, std::uint64_t max_bytes, bool text) {
  std::unique_ptr<std::FILE, decltype(&std::fclose)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file)
    throw InputError(path.string(), fmt::format("cannot open file ({})", std::strerror(errno)),
                     "check the path and its permissions");
  const auto too_large = [&] {
    return InputError(path.string(),
                      fmt::format("holds more than the {:.3g} MB this reader takes", double(max_bytes) / 1e6),
                      "is it the right file? (a device such as /dev/zero never ends)");
  };
  std::error_code ec;
  if (const auto size = fs::file_size(path, ec); !ec && size > max_bytes) throw too_large();
  std::string content;
  if (!ec) content.reserve(std::size_t(fs::file_size(path, ec)));
  std::size_t lines_before = 0;  // newlines before the current chunk, for the NUL's line number
  char chunk[1 << 16];
  for (;;) {
    const std::size_t got = std::fread(chunk, 1, sizeof chunk, file.get());
    if (got == 0) break;
    if (content.size() + got > max_bytes) throw too_large();
    if (text) require_text(std::string_view(chunk, got), path.string(), lines_before + 1, content.size());
    if (text) lines_before += std::size_t(std::count(chunk, chunk + got, '\n'));
    content.append(chunk, got);
  }
  if (std::ferror(file.get())) throw InputError(path.string(), "read error", "check the file");
  return content;
}

}  // namespace

std::string read_file(const fs::path& path, std::uint64_t max_bytes) {
  return read_whole(path, max_bytes, false);
}

std::string read_text_file(const fs::path& path, std::uint64_t max_bytes) {
  return read_whole(path, max_bytes, true);
}

void require_text(std::string_view text, const std::string& source, std::size_t first_line,
                  std::uint64_t bytes_before) {
  const auto nul = text.find('\0');
  if (nul == std::string_view::npos) return;
  const auto line =
      first_line + std::size_t(std::count(text.begin(), text.begin() + std::ptrdiff_t(nul), '\n'));
  throw InputError(fmt::format("{}:{}", source, line),
                   fmt::format("holds a NUL byte (byte {}): this is not a text file, or it is damaged",
                               bytes_before + nul + 1),
                   "give the text file (TOML, CSV) itself; a copy interrupted mid-way can end in NULs");
}

void write_output(const std::filesystem::path& target, std::string_view content) {
  if (target == "-") {
    std::fwrite(content.data(), 1, content.size(), stdout);
    std::fflush(stdout);
    return;
  }
  write_file_atomically(target, content);
}

}  // namespace rupture::io
