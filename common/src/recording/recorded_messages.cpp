#include "climbsim/recording/recorded_messages.hpp"

#include <mcap/reader.hpp>

#include "climbsim/errors.hpp"
#include "climbsim/recording/mcap_check.hpp"

namespace climbsim::recording {

std::map<std::string, std::vector<RecordedMessage>> readRecordedMessages(const std::string& path,
                                                                        const std::set<std::string>& topics) {
  const McapCheck check = checkMcap(path);
  if (!check.closed) throw ConfigError(path + ": " + check.problem + " (a replay needs a whole recording)");
  for (const auto& topic : topics) {
    if (!check.channels.count(topic)) throw ConfigError(path + ": no channel '" + topic + "' in the recording");
  }
  mcap::McapReader reader;
  if (const auto status = reader.open(path); !status.ok()) throw ConfigError(path + ": " + status.message);
  std::map<std::string, std::vector<RecordedMessage>> out;
  std::string problem;
  const auto on_problem = [&problem](const mcap::Status& status) { problem = status.message; };
  mcap::ReadMessageOptions options;
  options.topicFilter = [&topics](std::string_view topic) { return topics.count(std::string(topic)) > 0; };
  options.readOrder = mcap::ReadMessageOptions::ReadOrder::FileOrder;
  for (const auto& view : reader.readMessages(on_problem, options)) {
    const auto* data = reinterpret_cast<const std::uint8_t*>(view.message.data);
    out[view.channel->topic].push_back({static_cast<std::int64_t>(view.message.logTime),
                                        std::vector<std::uint8_t>(data, data + view.message.dataSize)});
  }
  reader.close();
  if (!problem.empty()) throw ConfigError(path + ": " + problem);
  return out;
}

std::set<std::string> topicList(const std::string& list) {
  std::set<std::string> out;
  std::size_t start = 0;
  while (start < list.size()) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    if (comma > start) out.insert(list.substr(start, comma - start));
    start = comma + 1;
  }
  return out;
}

}  // namespace climbsim::recording
