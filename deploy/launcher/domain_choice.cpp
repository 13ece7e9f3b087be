#include "domain_choice.hpp"

#include <stdexcept>

namespace climbsim::launcher {

DomainLease leaseRunDomain(std::optional<int> fixed, const std::string& lock_dir) {
  if (!fixed) {
    return DomainLease(kAutoDomainFirst, kAutoDomainLast, lock_dir);
  }
  try {
    return DomainLease(*fixed, *fixed, lock_dir);
  } catch (const std::runtime_error&) {
    throw std::runtime_error("DDS domain " + std::to_string(*fixed) +
                             " is used by another run or test on this machine (lock in " + lock_dir +
                             "); choose another with --domain N, or domain_id: auto in the compose file");
  }
}

}  // namespace climbsim::launcher
