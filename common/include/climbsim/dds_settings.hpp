#pragma once
/// @file
/// Where a climbsim process finds its DDS domain and its QoS profile file.

#include <cstddef>
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
  /// The largest sample this process writes [bytes], when it writes images: its shared-memory
  /// segment then holds kImagesInFlight of them beyond the QoS file's segment_size (which is
  /// sized for small samples). 0: small samples only. See shmSegmentBytes().
  std::size_t largest_sample_bytes = 0;

  /// Adds --domain and --qos to a command line.
  void addOptions(CLI::App& app);

  /// Fills what the command line left open from CLIMBSIM_DOMAIN and CLIMBSIM_QOS_FILE, then
  /// the built-in default QoS file, and validates: throws ConfigError naming the option or
  /// variable and the value if the domain is missing or outside 0..232 or the QoS file is
  /// unreadable.
  void resolve();
};

/// Samples of the largest size a process's shared-memory segment holds at once, beyond what
/// the QoS file's segment_size holds for its small samples.
inline constexpr std::size_t kImagesInFlight = 8;

/// The shared-memory segment [bytes] of a process that writes samples of up to
/// `largest_sample_bytes` (0: small samples only), given the QoS file's `base_bytes`:
/// base + kImagesInFlight * largest. Fast DDS writes the whole segment once when the
/// participant is created (about 1.3 ms of CPU per MiB here), so a process that writes no
/// images keeps the small base.
std::size_t shmSegmentBytes(std::size_t base_bytes, std::size_t largest_sample_bytes);

/// The bytes of an image sample of width_px x height_px pixels of `bytes_per_pixel` (4: a float
/// height), with room for its other fields: what DdsSettings::largest_sample_bytes takes.
inline std::size_t imageSampleBytes(std::size_t width_px, std::size_t height_px, std::size_t bytes_per_pixel = 4) {
  return width_px * height_px * bytes_per_pixel + 64 * 1024;
}

/// Parses a domain id given as `text` by `source` (an option or a variable name).
int parseDomainId(const std::string& source, const std::string& text);

}  // namespace climbsim
