#pragma once
/// @file
/// What an MCAP file holds, read record by record from its start without its summary (so a
/// file whose writer was killed reads up to its last complete record): messages per channel,
/// whether it was closed (footer), and where it ends if it is cut short or corrupt.
/// `./deploy/climbsim mcap-check FILE` prints it (docs/recordings.md#checking-a-recording).

#include <cstdint>
#include <map>
#include <string>

namespace climbsim::recording {

/// One channel's messages.
struct ChannelCount {
  std::string schema;           ///< schema name, e.g. "climbsim::ChamberState"
  std::string encoding;         ///< message encoding, e.g. "cdr"
  std::uint64_t messages = 0;
  std::int64_t last_log_time_ns = -1;  ///< -1: none
};

struct McapCheck {
  bool closed = false;          ///< the file ends with a footer and the closing magic
  std::string problem;          ///< empty, or why the file is not whole (cut short inside a record, corrupt)
  std::uint64_t good_bytes = 0; ///< the file reads correctly up to this offset [bytes]
  std::uint64_t chunks = 0;
  std::uint64_t metadata = 0;   ///< metadata records
  std::uint64_t file_bytes = 0;
  std::map<std::string, ChannelCount> channels;  ///< by topic
  std::uint64_t messages() const;
  std::int64_t lastLogTimeNs() const;  ///< -1: no message
};

/// Reads `path`. A file that cannot be opened or does not start with the MCAP magic gives
/// a McapCheck with `problem` set and nothing else.
McapCheck checkMcap(const std::string& path);

}  // namespace climbsim::recording
