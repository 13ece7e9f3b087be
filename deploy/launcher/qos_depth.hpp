#pragma once
/// @file
/// What the launcher needs of the QoS file before anything starts: how deep the step-data
/// queues are, which bounds the clock's window (a producer runs up to W steps ahead).

#include <cstdint>
#include <string>

namespace climbsim::launcher {

/// The smaller KEEP_LAST depth of the `climbsim.step_data` writer and reader profiles of the
/// Fast DDS XML file `qos_file`. Throws ConfigError naming the file if it does not parse or
/// lacks the profiles.
int stepDataQueueDepth(const std::string& qos_file);

/// Throws ConfigError (one line naming the option, the value and the file) unless
/// 1 <= window_steps <= depth - 2, the most the step-data queues of `qos_file` hold.
void checkWindowFitsQueues(std::uint32_t window_steps, const std::string& qos_file);

}  // namespace climbsim::launcher
