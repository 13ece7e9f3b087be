#pragma once
/// @file
/// The MCAP file of a run (RUN_DIR/run.mcap, docs/recordings.md), written with the MCAP
/// project's C++ library (common/third_party/mcap): chunked, indexed, zstd-compressed. Every
/// closed chunk is flushed to the file at once, so a process killed mid-run leaves a file that
/// reads up to its last closed chunk; close() adds the summary and the footer.

#include <cstdint>
#include <map>
#include <memory>
#include <string>

namespace mcap {
class McapWriter;
}

namespace climbsim::recording {

/// The MCAP profile of climbsim's recordings (the header's profile field).
inline constexpr const char* kMcapProfile = "climbsim";

class McapRunFile {
 public:
  /// Creates `path` (replacing a file there). ConfigError naming the path if it cannot.
  explicit McapRunFile(const std::string& path);
  ~McapRunFile();  ///< close()
  McapRunFile(const McapRunFile&) = delete;
  McapRunFile& operator=(const McapRunFile&) = delete;

  /// A channel of `topic` whose messages are CDR samples (with their encapsulation header) of
  /// the IDL type `type_name` ("climbsim::ChamberState"): schema encoding `omgidl` with the
  /// type's self-contained IDL text from idl/ (omgidl_schema.hpp), message encoding `cdr`.
  /// Returns the channel id; one schema per type however many channels use it.
  std::uint16_t addCdrChannel(const std::string& topic, const std::string& type_name);

  /// A channel with a schema given as it is (name, encoding, data) and `message_encoding`.
  std::uint16_t addChannel(const std::string& topic, const std::string& message_encoding,
                           const std::string& schema_name, const std::string& schema_encoding,
                           const std::string& schema_data);

  /// A message of `channel`: log and publish time `t_ns` [ns of simulated time]. Throws
  /// std::runtime_error if the library refuses it.
  void write(std::uint16_t channel, std::int64_t t_ns, const void* data, std::size_t size);

  /// A metadata record `name` with its key-value pairs (written after the current chunk).
  void metadata(const std::string& name, const std::map<std::string, std::string>& values);

  /// Closes the chunk under way (if any) and flushes it to the file.
  void closeChunk();

  /// Closes the last chunk, writes the summary (schemas, channels, statistics, chunk and
  /// metadata indexes) and the footer; idempotent.
  void close();

 private:
  std::unique_ptr<mcap::McapWriter> writer_;
  std::map<std::string, std::uint16_t> schemas_;  ///< by schema name
  std::map<std::uint16_t, std::uint32_t> sequence_;  ///< next sequence number by channel
  std::string path_;
  bool open_ = false;
};

}  // namespace climbsim::recording
