#include "climbsim/sender_identity.hpp"

#include <spdlog/spdlog.h>

#include "climbsim/run_stats.hpp"

namespace climbsim {

std::string participantIdHex(const ParticipantId& id) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string hex(2 * ParticipantId::size, '0');
  for (std::size_t i = 0; i < ParticipantId::size; ++i) {
    hex[2 * i] = kDigits[id.value[i] >> 4];
    hex[2 * i + 1] = kDigits[id.value[i] & 0x0f];
  }
  return hex;
}

std::optional<ParticipantId> participantIdFromHex(const std::string& hex) {
  if (hex.size() != 2 * ParticipantId::size) {
    return std::nullopt;
  }
  auto nibble = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
  };
  ParticipantId id;
  for (std::size_t i = 0; i < ParticipantId::size; ++i) {
    const int high = nibble(hex[2 * i]);
    const int low = nibble(hex[2 * i + 1]);
    if (high < 0 || low < 0) {
      return std::nullopt;
    }
    id.value[i] = static_cast<eprosima::fastrtps::rtps::octet>(high << 4 | low);
  }
  return id;
}

void SenderLog::drop(const std::string& topic, const std::string& writer, const std::string& why) {
  ++dropped_;
  statsAdd("foreign_samples_dropped", 1.0);
  if (logged_.size() < 1024 && logged_.insert(writer).second) {
    spdlog::warn("{}: dropped a sample of '{}' from writer {}: {} (counted, logged once per writer)", who_, topic,
                 writer, why);
  }
}

}  // namespace climbsim
