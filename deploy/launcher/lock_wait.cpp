#include "lock_wait.hpp"

#include <poll.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>

#include "file_lock.hpp"

namespace climbsim::launcher {

namespace {
int openPidFd(pid_t pid) {
#ifdef SYS_pidfd_open
  return static_cast<int>(::syscall(SYS_pidfd_open, pid, 0));
#else
  (void)pid;
  return -1;
#endif
}
}  // namespace

bool waitForLockRelease(const std::string& lock_path, std::chrono::steady_clock::time_point deadline) {
  using namespace std::chrono;
  while (FileLock::isHeld(lock_path)) {
    const auto left = ceil<milliseconds>(deadline - steady_clock::now()).count();
    if (left <= 0) {
      return false;
    }
    const auto owner = FileLock::readOwner(lock_path);
    const int pid_fd = owner ? openPidFd(*owner) : -1;
    if (pid_fd >= 0) {
      // Readable when the owner has exited. The lock file may name a parent that handed the
      // lock to a daemon: the loop then reads the new owner.
      pollfd fd{pid_fd, POLLIN, 0};
      ::poll(&fd, 1, static_cast<int>(std::min<long long>(left, 1000)));
      ::close(pid_fd);
    } else {
      ::poll(nullptr, 0, static_cast<int>(std::min<long long>(left, 10)));
    }
  }
  return true;
}

}  // namespace climbsim::launcher
