// io/file_lock: exclusive locks that the kernel drops when their holder exits, however it exits
// (Linux open-file-description locks on a lock file), so a killed process never leaves anything
// locked. They serve the claim on a scan point and the one-writer rule of every output folder.
// Not: what a folder holds or when it may be written (loading/run, scan/ledger).
#pragma once

#include <filesystem>
#include <string>

namespace rupture::io {

class FileLock {
 public:
  // Tries once, without waiting; held() says whether it was taken. Throws RunError when the lock
  // file cannot be created.
  explicit FileLock(const std::filesystem::path& file);
  ~FileLock();
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;
  bool held() const { return held_; }
  // Leaves `text` (who holds it) in the lock file, for the message another writer gets.
  void describe_holder(const std::string& text);

 private:
  int fd_;
  bool held_ = false;
};

// True when some process (this one included) holds the lock now. Only looks: a probe never takes
// the lock, even for a moment, so it cannot make a writer fail.
bool is_locked(const std::filesystem::path& file);

// The one-writer rule of an output folder: FOLDER/.rupture-lock, held for this object's lifetime.
// The folder must exist. Throws InputError naming the folder and the process that holds it.
class FolderLock {
 public:
  FolderLock(const std::filesystem::path& folder, const std::string& command);

 private:
  FileLock lock_;
};

inline constexpr const char* folder_lock_name = ".rupture-lock";

}  // namespace rupture::io
