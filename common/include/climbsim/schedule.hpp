#pragma once
/// @file
/// When a lockstep participant is due, and which stamp it reads from a producer.

#include <cstdint>
#include <optional>
#include <string>

namespace climbsim {

/// A participant's multi-rate schedule in steps (docs/design.md#multi-rate-schedules): due at every
/// step k with k >= offset_steps and (k - offset_steps) % period_steps == 0.
struct Schedule {
  std::uint32_t period_steps = 1;  ///< >= 1
  std::uint32_t offset_steps = 0;  ///< < period_steps

  /// Throws ConfigError naming `what` if period_steps is 0 or offset_steps >= period_steps.
  void validate(const std::string& what) const;

  /// True if the participant computes step `step`.
  bool isDue(std::uint64_t step) const;

  /// The last step < `step` at which the participant was due, or nothing if it has not
  /// been due yet. This is the stamp a consumer at `step` reads from this producer:
  /// inputs come from earlier steps, held (zero-order hold) until the producer's next step.
  std::optional<std::uint64_t> lastDueBefore(std::uint64_t step) const;

  /// The first step >= `step` at which the participant is due.
  std::uint64_t nextDueFrom(std::uint64_t step) const;

  /// Number of due steps in [0, end_step).
  std::uint64_t dueCount(std::uint64_t end_step) const;
};

}  // namespace climbsim
