#pragma once
/// @file
/// The DDS domain of a run: fixed by the compose file or picked free (`domain_id: auto`),
/// and held with a climbsim::DomainLease for as long as the supervisor lives, so that
/// concurrent runs (and tests) on one machine never meet.

#include <optional>
#include <string>

#include "climbsim/domain_lease.hpp"

namespace climbsim::launcher {

/// Domain ids `domain_id: auto` picks from; the tests lease ids >= 100.
inline constexpr int kAutoDomainFirst = 10;
inline constexpr int kAutoDomainLast = 99;

/// Where runs and tests keep their domain locks (climbsim::DomainLease's default).
inline constexpr const char* kDomainLockDir = "/tmp/climbsim-domains";

/// Leases `fixed` if given, else the first free id in kAutoDomainFirst..kAutoDomainLast.
/// Throws std::runtime_error with a one-line message if the id (or every id) is taken.
DomainLease leaseRunDomain(std::optional<int> fixed, const std::string& lock_dir = kDomainLockDir);

}  // namespace climbsim::launcher
