#include "io/file_lock.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/error.hpp"

namespace rupture::io {

namespace {

// OFD locks rather than flock because they can be queried without being taken (is_locked).
struct flock whole_file(short type) {
  struct flock lock {};
  lock.l_type = type;
  lock.l_whence = SEEK_SET;  // l_start = l_len = 0: the whole file
  return lock;
}

std::string holder_text(const std::filesystem::path& file) {
  const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return {};
  char buffer[200];
  const ssize_t n = ::read(fd, buffer, sizeof buffer);
  ::close(fd);
  std::string text(buffer, n > 0 ? std::size_t(n) : 0);
  if (const auto end = text.find('\n'); end != std::string::npos) text.resize(end);
  return text;
}

}  // namespace

FileLock::FileLock(const std::filesystem::path& file)
    : fd_(::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644)) {
  if (fd_ < 0)
    throw RunError(fmt::format("{}: cannot open the lock file ({})", file.string(), std::strerror(errno)));
  struct flock lock = whole_file(F_WRLCK);
  held_ = ::fcntl(fd_, F_OFD_SETLK, &lock) == 0;
}

FileLock::~FileLock() { ::close(fd_); }

void FileLock::describe_holder(const std::string& text) {
  const std::string line = text.substr(0, 150) + "\n";
  // Best effort: the lock works without it; only the refusal's wording would lose the holder.
  if (::ftruncate(fd_, 0) == 0) (void)!::pwrite(fd_, line.data(), line.size(), 0);
}

bool is_locked(const std::filesystem::path& file) {
  const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;  // never claimed
  struct flock lock = whole_file(F_WRLCK);
  const bool locked = ::fcntl(fd, F_OFD_GETLK, &lock) == 0 && lock.l_type != F_UNLCK;
  ::close(fd);
  return locked;
}

FolderLock::FolderLock(const std::filesystem::path& folder, const std::string& command)
    : lock_(folder / folder_lock_name) {
  if (!lock_.held()) {
    const std::string holder = holder_text(folder / folder_lock_name);
    throw InputError(
        folder.string(),
        fmt::format("is being written by another process ({})", holder.empty() ? "another rupture" : holder),
        "wait for it to end, or choose another output folder");
  }
  lock_.describe_holder(fmt::format("pid {}: {}", ::getpid(), command));
}

}  // namespace rupture::io
