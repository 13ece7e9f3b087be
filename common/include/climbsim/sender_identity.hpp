#pragma once
/// @file
/// Who sent a sample: the 12-byte RTPS GUID prefix of the DDS participant
/// behind its writer. A climbsim participant's identity is the prefix of the DDS
/// participant that announced it ready, fixed by the clock at ready time and published in
/// RunStart.identities as 24 lowercase hex digits. Samples from any other DDS participant
/// are dropped, counted, and logged once per writer (SenderLog).

#include <fastdds/rtps/common/GuidPrefix_t.hpp>

#include <cstdint>
#include <optional>
#include <set>
#include <string>

namespace climbsim {

/// The GUID prefix of a DDS participant: 2 bytes vendor, 10 bytes host/process/participant.
using ParticipantId = eprosima::fastrtps::rtps::GuidPrefix_t;

/// 24 lowercase hex digits of the 12 bytes, in wire order (what RunStart.identities carries).
std::string participantIdHex(const ParticipantId& id);
/// The prefix of 24 hex digits, or nothing if `hex` is not that.
std::optional<ParticipantId> participantIdFromHex(const std::string& hex);

/// Dropped samples of senders that are not who they must be: counted, and logged once per
/// writer (its GUID) so that a flood costs one line.
class SenderLog {
 public:
  /// `who`: the receiving process, for the log ("clock", a participant name).
  explicit SenderLog(std::string who) : who_(std::move(who)) {}
  /// Counts one dropped sample of `topic` from `writer` (writerKey); logs it if it is the
  /// first from that writer, with `why`.
  void drop(const std::string& topic, const std::string& writer, const std::string& why);
  /// Samples dropped so far.
  std::uint64_t dropped() const { return dropped_; }

 private:
  std::string who_;
  std::set<std::string> logged_;
  std::uint64_t dropped_ = 0;
};

}  // namespace climbsim
