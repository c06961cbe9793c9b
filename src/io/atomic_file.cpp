#include "io/atomic_file.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include <fmt/format.h>
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
    throw RunError(fmt::format("{}: write failed ({}); is the disk full?", target_.string(), std::strerror(errno)));
  }
}

void AtomicFile::commit() {
  const bool flushed = std::fflush(file_) == 0 && fsync(fileno(file_)) == 0;
  const int error = errno;
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  if (!flushed || !closed) {
    throw RunError(fmt::format("{}: write failed ({}); is the disk full? the previous file is kept",
                               target_.string(), std::strerror(error)));
  }
  std::error_code ec;
  fs::rename(temporary_, target_, ec);
  if (ec) throw RunError(fmt::format("{}: cannot replace file ({})", target_.string(), ec.message()));
  committed_ = true;
}

void write_file_atomically(const fs::path& target, std::string_view content) {
  AtomicFile file(target);
  file.write(content);
  file.commit();
}

void write_json_atomically(const fs::path& target, const nlohmann::json& document) {
  write_file_atomically(target, document.dump(2) + "\n");
}

std::string read_text_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw InputError(path.string(), fmt::format("cannot open file ({})", std::strerror(errno)),
                     "check the path and its permissions");
  }
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw InputError(path.string(), "read error", "check the file");
  return std::move(buffer).str();
}

}  // namespace rupture::io
