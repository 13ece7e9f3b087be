#pragma once
/// @file
/// Who may send ClockControl (compose `clock.control`): DDS participant names,
/// each optionally bound to the host addresses its participant must announce. The clock
/// node checks every ClockControl sample's DDS participant (name and UDPv4 addresses from
/// discovery) against this list; without DDS Security names and addresses can be forged,
/// with it the permissions document is what binds (docs/deployment.md#dds-security).

#include <string>
#include <vector>

namespace climbsim::clock {

/// The address that stands for "on the clock's own machine": a participant that the clock
/// reaches through shared memory (Fast DDS announces only shared-memory locators then).
inline constexpr const char* kSharedMemoryAddress = "shm";

/// One allowed sender: a DDS participant name and, if not empty, the addresses (IPv4,
/// dotted) of which its participant must announce at least one.
struct ControlSender {
  std::string name;
  std::vector<std::string> addresses;
};

/// Parses `--control-from` text "name[@addr[/addr...]][,name...]"; throws ConfigError
/// naming `option` and the entry if a name is invalid or an address is empty.
std::vector<ControlSender> parseControlSenders(const std::string& option, const std::string& text);

/// The list as text, the inverse of parseControlSenders.
std::string formatControlSenders(const std::vector<ControlSender>& senders);

/// Empty if a DDS participant named `name` announcing `addresses` may send ClockControl,
/// else why not (for the log).
std::string controlRefusal(const std::vector<ControlSender>& allowed, const std::string& name,
                           const std::vector<std::string>& addresses);

}  // namespace climbsim::clock
