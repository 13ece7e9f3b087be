#pragma once
/// @file
/// The messages of a recording (RUN_DIR/run.mcap, docs/recordings.md) as they are on the file:
/// the CDR bytes of each channel in file order, for a replay to play back or a recorded
/// controller to decode. No DDS.

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace climbsim::recording {

/// One recorded message: its log time [ns] and its CDR bytes (encapsulation included).
struct RecordedMessage {
  std::int64_t t_ns = 0;
  std::vector<std::uint8_t> cdr;
};

/// The messages of `topics` in the recording `path`, by topic, in file order. ConfigError (one
/// line naming the file) if it is no MCAP file, is cut short or corrupt (a replay needs a whole
/// recording), or has no channel of a topic asked for.
std::map<std::string, std::vector<RecordedMessage>> readRecordedMessages(const std::string& path,
                                                                        const std::set<std::string>& topics);

/// The comma-separated topic names of `list` ("" for none).
std::set<std::string> topicList(const std::string& list);

}  // namespace climbsim::recording
