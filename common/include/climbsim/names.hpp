#pragma once
/// @file
/// Participant and topic names: what the control plane accepts.

#include <set>
#include <string>
#include <vector>

namespace climbsim {

/// Longest participant or topic name (the IDL bounds strings to 64 bytes with the NUL).
inline constexpr std::size_t kMaxNameLength = 63;

/// Throws ConfigError naming `what` and `name` unless `name` is 1..63 characters of
/// [A-Za-z0-9_.-].
void validateName(const std::string& what, const std::string& name);

/// Splits "a,b,c" into names (empty items are an error), validating each.
std::vector<std::string> parseNameList(const std::string& what, const std::string& list);

/// The one parser of the services' `--inputs` lists: which of `choices` "a,b" selects (any
/// subset, in any order), "none" for none. ConfigError "OPTION = 'LIST': unknown input 'x'
/// (choose from a, b, c, or none)" for a name not among `choices`, and parseNameList's errors.
std::set<std::string> parseChoiceList(const std::string& option, const std::string& list,
                                      const std::vector<std::string>& choices);

/// "a, b, c"
std::string joinNames(const std::vector<std::string>& names);

}  // namespace climbsim
