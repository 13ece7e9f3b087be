#include "recorded_commands_file.hpp"

#include <fastdds/rtps/common/SerializedPayload.h>

#include <cmath>
#include <cstring>
#include <set>
#include <sstream>

#include "climbsim/errors.hpp"
#include "climbsim/recording/mcap_check.hpp"
#include "climbsim/recording/recorded_messages.hpp"
#include "climbsim/topic_names.hpp"
#include "thermoPubSubTypes.h"

namespace climbsim::controller {
namespace {

template <class PubSubT, class Sample>
Sample decode(const std::string& file, const char* topic, const recording::RecordedMessage& message) {
  eprosima::fastrtps::rtps::SerializedPayload_t payload(static_cast<std::uint32_t>(message.cdr.size()));
  std::memcpy(payload.data, message.cdr.data(), message.cdr.size());
  payload.length = static_cast<std::uint32_t>(message.cdr.size());
  PubSubT type;
  Sample sample;
  if (!type.deserialize(&payload, &sample)) {
    throw ConfigError(file + ": a " + topic + " message at t = " + std::to_string(message.t_ns * 1e-9) +
                      " s does not decode");
  }
  return sample;
}

std::string seconds(std::int64_t t_ns) {
  std::ostringstream text;
  text << static_cast<double>(t_ns) * 1e-9 << " s";
  return text.str();
}

/// ConfigError unless every value is finite and in [0, 1] and there are `expected` of them.
void checkValues(const std::string& file, const char* topic, const char* what, std::int64_t t_ns,
                 const std::vector<double>& values, std::size_t expected, const char* unit_of_count) {
  if (values.size() != expected) {
    throw ConfigError(file + ": " + topic + " at t = " + seconds(t_ns) + " has " + std::to_string(values.size()) +
                      " " + what + ", the robot has " + std::to_string(expected) + " " + unit_of_count);
  }
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!(std::isfinite(values[i]) && values[i] >= 0.0 && values[i] <= 1.0)) {
      std::ostringstream text;
      text << file << ": " << topic << " at t = " << seconds(t_ns) << ": " << what << "[" << i << "] = " << values[i]
           << " (must be in [0, 1])";
      throw ConfigError(text.str());
    }
  }
}

/// ConfigError if `source` is not the first writer's or `t_ns` goes back in time.
void checkOrder(const std::string& file, const char* topic, std::string& writer, const std::string& source,
                std::int64_t last_t_ns, std::int64_t t_ns) {
  if (writer.empty()) writer = source;
  if (source != writer) {
    throw ConfigError(file + ": " + topic + " has two writers, '" + writer + "' and '" + source +
                      "'; a recorded controller plays one back");
  }
  if (t_ns < last_t_ns) {
    throw ConfigError(file + ": " + topic + " goes back in time, from " + seconds(last_t_ns) + " to " + seconds(t_ns));
  }
}

}  // namespace

RecordedCommands readRecordedCommands(const std::string& file, const RobotGeometry& geometry, int engine_count,
                                      std::int64_t duration_ns) {
  const recording::McapCheck check = recording::checkMcap(file);
  if (!check.closed) {
    throw ConfigError(file + ": " + check.problem + " (a recorded controller needs a whole recording)");
  }
  std::set<std::string> topics;
  for (const char* topic : {topic::kValveCommand, topic::kEngineCommand, topic::kStop}) {
    if (check.channels.count(topic)) topics.insert(topic);
  }
  if (!topics.count(topic::kValveCommand) && !topics.count(topic::kEngineCommand)) {
    throw ConfigError(file + ": no " + topic::kValveCommand + " or " + topic::kEngineCommand +
                      " channel (record the run with recording.commands: true)");
  }
  const auto messages = recording::readRecordedMessages(file, topics);
  RecordedCommands out;
  out.file = file;
  const auto stop = messages.find(topic::kStop);
  if (stop == messages.end() || stop->second.empty()) {
    throw ConfigError(file + ": no " + topic::kStop + " message: the recording does not say where its run stopped");
  }
  out.end_ns = stop->second.back().t_ns;
  if (const auto valves = messages.find(topic::kValveCommand); valves != messages.end()) {
    const std::size_t count = geometry.has_reservoir ? static_cast<std::size_t>(geometry.chamberCount()) : 0;
    std::string writer;
    for (const auto& message : valves->second) {
      const auto v = decode<ValveCommandPubSubType, ValveCommand>(file, topic::kValveCommand, message);
      checkOrder(file, topic::kValveCommand, writer, v.source().to_string(),
                 out.valves.empty() ? 0 : out.valves.back().t_ns, v.t_ns());
      const std::vector<double> opening(v.opening().begin(), v.opening().end());
      checkValues(file, topic::kValveCommand, "openings", v.t_ns(), opening, count, "valves");
      out.valves.push_back({v.t_ns(), opening, v.downforce_setpoint_n()});
    }
  }
  if (const auto engines = messages.find(topic::kEngineCommand); engines != messages.end()) {
    std::string writer;
    for (const auto& message : engines->second) {
      const auto e = decode<EngineCommandPubSubType, EngineCommand>(file, topic::kEngineCommand, message);
      checkOrder(file, topic::kEngineCommand, writer, e.source().to_string(),
                 out.engines.empty() ? 0 : out.engines.back().t_ns, e.t_ns());
      std::vector<double> speed;
      for (const auto& engine : e.engines()) speed.push_back(engine.on() ? engine.speed() : 0.0);
      checkValues(file, topic::kEngineCommand, "engine speeds", e.t_ns(), speed,
                  static_cast<std::size_t>(engine_count), "engines");
      out.engines.push_back({e.t_ns(), std::move(speed)});
    }
  }
  if (duration_ns > out.end_ns) {
    throw ConfigError(file + ": the recorded run stopped at " + seconds(out.end_ns) + ", this run lasts " +
                      seconds(duration_ns) + " (duration_s must be at most the recording's)");
  }
  return out;
}

}  // namespace climbsim::controller
