#pragma once
/// @file
/// A DDS domain id held for the lifetime of a run or a test, so that concurrent runs and
/// tests on one machine never meet (docs/design.md#topics-and-qos).

#include <string>

namespace climbsim {

/// Holds an exclusive lock on one domain id of a range while it lives. The locks are
/// flock()s on files in a directory shared by every process of the machine; a crashed
/// holder releases its lock with its process.
class DomainLease {
 public:
  /// Takes the first free id in [first, last]; throws std::runtime_error if none is free.
  DomainLease(int first, int last, const std::string& lock_dir = "/tmp/climbsim-domains");
  ~DomainLease();
  DomainLease(DomainLease&& other) noexcept;
  DomainLease(const DomainLease&) = delete;
  DomainLease& operator=(const DomainLease&) = delete;
  DomainLease& operator=(DomainLease&&) = delete;

  int id() const { return id_; }

 private:
  int id_ = -1;
  int fd_ = -1;
};

}  // namespace climbsim
