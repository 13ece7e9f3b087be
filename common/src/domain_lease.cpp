#include "climbsim/domain_lease.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace climbsim {

DomainLease::DomainLease(int first, int last, const std::string& lock_dir) {
  if (::mkdir(lock_dir.c_str(), 01777) != 0 && errno != EEXIST) {
    throw std::runtime_error("cannot create '" + lock_dir + "': " + std::strerror(errno));
  }
  ::chmod(lock_dir.c_str(), 01777);
  for (int id = first; id <= last; ++id) {
    const std::string path = lock_dir + "/" + std::to_string(id) + ".lock";
    const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
    if (fd < 0) {
      continue;
    }
    if (::flock(fd, LOCK_EX | LOCK_NB) == 0) {
      id_ = id;
      fd_ = fd;
      return;
    }
    ::close(fd);
  }
  throw std::runtime_error("no free DDS domain id in " + std::to_string(first) + ".." + std::to_string(last) +
                           " (locks in " + lock_dir + ")");
}

DomainLease::~DomainLease() {
  if (fd_ >= 0) {
    ::close(fd_);  // releases the flock
  }
}

DomainLease::DomainLease(DomainLease&& other) noexcept : id_(other.id_), fd_(other.fd_) {
  other.fd_ = -1;
  other.id_ = -1;
}

}  // namespace climbsim
