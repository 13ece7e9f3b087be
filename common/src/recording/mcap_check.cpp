#include "climbsim/recording/mcap_check.hpp"

#include <mcap/reader.hpp>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <memory>
#include <cstring>
#include <unordered_map>

namespace climbsim::recording {

std::uint64_t McapCheck::messages() const {
  std::uint64_t n = 0;
  for (const auto& [topic, c] : channels) n += c.messages;
  return n;
}

std::int64_t McapCheck::lastLogTimeNs() const {
  std::int64_t t = -1;
  for (const auto& [topic, c] : channels) t = std::max(t, c.last_log_time_ns);
  return t;
}

McapCheck checkMcap(const std::string& path) {
  McapCheck check;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> stream(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!stream) {
    check.problem = std::string("cannot read it (") + std::strerror(errno) + ")";
    return check;
  }
  mcap::FileReader file(stream.get());
  check.file_bytes = file.size();
  std::byte* magic = nullptr;
  if (file.size() < sizeof(mcap::Magic) || file.read(&magic, 0, sizeof(mcap::Magic)) != sizeof(mcap::Magic) ||
      std::memcmp(magic, mcap::Magic, sizeof(mcap::Magic)) != 0) {
    check.problem = "not an MCAP file (no MCAP magic at its start)";
    return check;
  }
  std::unordered_map<mcap::SchemaId, std::string> schemas;
  std::unordered_map<mcap::ChannelId, std::string> topics;
  mcap::TypedRecordReader reader(file, sizeof(mcap::Magic));
  std::uint64_t footer_end = 0;
  reader.onSchema = [&](const mcap::SchemaPtr s, mcap::ByteOffset, std::optional<mcap::ByteOffset>) {
    schemas[s->id] = s->name;
  };
  reader.onChannel = [&](const mcap::ChannelPtr c, mcap::ByteOffset, std::optional<mcap::ByteOffset>) {
    topics[c->id] = c->topic;
    auto& count = check.channels[c->topic];
    count.schema = schemas.count(c->schemaId) ? schemas[c->schemaId] : "";
    count.encoding = c->messageEncoding;
  };
  std::string unknown_channel;
  reader.onMessage = [&](const mcap::Message& m, mcap::ByteOffset, std::optional<mcap::ByteOffset>) {
    const auto topic = topics.find(m.channelId);
    if (topic == topics.end()) {
      unknown_channel = "a message of channel " + std::to_string(m.channelId) + ", which no channel record declares";
      return;
    }
    auto& count = check.channels[topic->second];
    ++count.messages;
    count.last_log_time_ns = std::max(count.last_log_time_ns, static_cast<std::int64_t>(m.logTime));
  };
  bool in_chunk = false;  // offset() counts inside the chunk's records then
  std::uint64_t good = sizeof(mcap::Magic);
  reader.onChunk = [&](const mcap::Chunk&, mcap::ByteOffset) { in_chunk = true; };
  reader.onChunkEnd = [&](mcap::ByteOffset end) {
    in_chunk = false;
    ++check.chunks;
    good = std::max<std::uint64_t>(good, end);
  };
  reader.onMetadata = [&](const mcap::Metadata&, mcap::ByteOffset) { ++check.metadata; };
  reader.onFooter = [&](const mcap::Footer&, mcap::ByteOffset offset) {
    footer_end = offset + 1 + 8 + 8 + 8 + 4;  // opcode, length, summary start, summary offset start, crc
  };
  while (reader.next()) {
    if (!reader.status().ok() || !unknown_channel.empty()) break;
    if (!in_chunk && reader.offset() != mcap::EndOffset) good = std::max<std::uint64_t>(good, reader.offset());
  }
  if (!unknown_channel.empty()) {
    check.problem = "corrupt: " + unknown_channel;
  } else if (!reader.status().ok()) {
    check.problem = "corrupt or cut short after byte " + std::to_string(good) + " (" + reader.status().message + ")";
  }
  if (footer_end > 0) {
    good = footer_end;
    std::byte* end_magic = nullptr;
    check.closed = file.size() == footer_end + sizeof(mcap::Magic) &&
                   file.read(&end_magic, footer_end, sizeof(mcap::Magic)) == sizeof(mcap::Magic) &&
                   std::memcmp(end_magic, mcap::Magic, sizeof(mcap::Magic)) == 0;
    if (check.closed) good = file.size();
    if (!check.closed && check.problem.empty()) check.problem = "no closing magic after its footer";
  } else if (check.problem.empty()) {
    check.problem = "not closed: no footer after byte " + std::to_string(good);
  }
  check.good_bytes = good;
  return check;
}

}  // namespace climbsim::recording
