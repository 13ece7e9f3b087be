#pragma once
/// @file
/// Where a climbsim process finds its DDS domain and its QoS profile file.

#include <optional>
#include <string>

namespace CLI {
class App;
}

namespace climbsim {

/// Largest domain id Fast DDS accepts with its default port mapping
/// (port 7400 + 250 * domain must stay below 65536).
inline constexpr int kMaxDomainId = 232;

/// DDS settings of one process: every run and every test uses its own domain id.
struct DdsSettings {
  int domain_id = -1;       ///< 0..232
  std::string qos_file;     ///< the QoS XML profile file (deploy/qos/climbsim.xml)
  std::string domain_text;  ///< --domain as given, parsed by resolve()

  /// Adds --domain and --qos to a command line.
  void addOptions(CLI::App& app);

  /// Fills what the command line left open from CLIMBSIM_DOMAIN and CLIMBSIM_QOS_FILE, then
  /// the built-in default QoS file, and validates: throws ConfigError naming the option or
  /// variable and the value if the domain is missing or outside 0..232 or the QoS file is
  /// unreadable.
  void resolve();
};

/// Parses a domain id given as `text` by `source` (an option or a variable name).
int parseDomainId(const std::string& source, const std::string& text);

}  // namespace climbsim
