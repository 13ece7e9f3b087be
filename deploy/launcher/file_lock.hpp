#pragma once
/// @file
/// Advisory whole-file locks (flock): held while the descriptor is open, released by the
/// kernel when the holder dies, so a lock file never goes stale.

#include <sys/types.h>

#include <optional>
#include <string>

namespace climbsim::launcher {

/// An exclusive lock on one file, held until destruction. The descriptor is close-on-exec:
/// started programs do not hold it, forked copies of this process do.
class FileLock {
 public:
  /// Takes the lock on `path` (created with mode 0644 if missing) without waiting; nothing
  /// if another open file holds it or the file cannot be opened for writing.
  static std::optional<FileLock> tryLock(const std::string& path);

  /// True if some process holds a lock on `path` (a missing file is not held).
  static bool isHeld(const std::string& path);

  /// The pid written into `path` by its holder, or nothing.
  static std::optional<pid_t> readOwner(const std::string& path);

  ~FileLock();
  FileLock(FileLock&& other) noexcept;
  FileLock& operator=(FileLock&& other) noexcept;
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;

  /// Replaces the file's content with `pid` (who holds it, for messages).
  void writeOwner(pid_t pid);

  const std::string& path() const { return path_; }

 private:
  FileLock(std::string path, int fd) : path_(std::move(path)), fd_(fd) {}

  std::string path_;
  int fd_ = -1;
};

}  // namespace climbsim::launcher
