#include "climbsim/recording/mcap_run_file.hpp"

#include <mcap/writer.hpp>

#include <stdexcept>

#include "climbsim/errors.hpp"
#include "climbsim/recording/omgidl_schema.hpp"

namespace climbsim::recording {

McapRunFile::McapRunFile(const std::string& path) : writer_(std::make_unique<mcap::McapWriter>()), path_(path) {
  mcap::McapWriterOptions options(kMcapProfile);
  options.compression = mcap::Compression::Zstd;
  // zstd level -3: a third less CPU than level 1 for a tenth more bytes (docs/recordings.md#what-recording-costs).
  options.compressionLevel = mcap::CompressionLevel::Fast;
  // Chunks close at this size or when the owner closes them (every simulated second).
  options.chunkSize = 4 * 1024 * 1024;
  const mcap::Status status = writer_->open(path, options);
  if (!status.ok()) throw ConfigError(path + ": cannot write (" + status.message + ")");
  open_ = true;
}

McapRunFile::~McapRunFile() { close(); }

std::uint16_t McapRunFile::addChannel(const std::string& topic, const std::string& message_encoding,
                                      const std::string& schema_name, const std::string& schema_encoding,
                                      const std::string& schema_data) {
  auto found = schemas_.find(schema_name);
  if (found == schemas_.end()) {
    mcap::Schema schema(schema_name, schema_encoding, schema_data);
    writer_->addSchema(schema);
    found = schemas_.emplace(schema_name, schema.id).first;
  }
  mcap::Channel channel(topic, message_encoding, found->second);
  writer_->addChannel(channel);
  sequence_[channel.id] = 0;
  return channel.id;
}

std::uint16_t McapRunFile::addCdrChannel(const std::string& topic, const std::string& type_name) {
  const std::string text = schemas_.count(type_name) ? std::string() : omgidlSchemaText(type_name);
  return addChannel(topic, "cdr", type_name, "omgidl", text);
}

void McapRunFile::write(std::uint16_t channel, std::int64_t t_ns, const void* data, std::size_t size) {
  mcap::Message message;
  message.channelId = channel;
  message.sequence = sequence_[channel]++;
  message.logTime = static_cast<mcap::Timestamp>(t_ns);
  message.publishTime = message.logTime;
  message.dataSize = size;
  message.data = static_cast<const std::byte*>(data);
  const mcap::Status status = writer_->write(message);
  if (!status.ok()) throw std::runtime_error(path_ + ": " + status.message);
}

void McapRunFile::metadata(const std::string& name, const std::map<std::string, std::string>& values) {
  mcap::Metadata record;
  record.name = name;
  record.metadata = mcap::KeyValueMap(values.begin(), values.end());
  const mcap::Status status = writer_->write(record);
  if (!status.ok()) throw std::runtime_error(path_ + ": " + status.message);
  writer_->dataSink()->flush();
}

void McapRunFile::closeChunk() {
  writer_->closeLastChunk();
  writer_->dataSink()->flush();  // the chunk and its message indexes reach the file now
}

void McapRunFile::close() {
  if (!open_) return;
  open_ = false;
  writer_->close();
}

}  // namespace climbsim::recording
