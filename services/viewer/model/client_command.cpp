#include "client_command.hpp"

#include <cmath>

#include <nlohmann/json.hpp>

namespace climbsim::viewer {

std::variant<ClockRequest, std::string> parseClientMessage(const std::string& text) {
  constexpr std::size_t kMaxLength = 4096;
  if (text.size() > kMaxLength) return std::string("message longer than 4096 bytes");
  const auto message = nlohmann::json::parse(text, nullptr, false);
  if (message.is_discarded() || !message.is_object()) return std::string("not a JSON object");
  const auto cmd = message.find("cmd");
  if (cmd == message.end() || !cmd->is_string()) return std::string("no \"cmd\" string");
  const std::string name = cmd->get<std::string>();
  ClockRequest request;
  if (name == "pause") {
    request.kind = ClockRequest::Kind::kPause;
  } else if (name == "resume") {
    request.kind = ClockRequest::Kind::kResume;
  } else if (name == "stop") {
    request.kind = ClockRequest::Kind::kStop;
  } else if (name == "step") {
    request.kind = ClockRequest::Kind::kStep;
    const auto steps = message.find("steps");
    if (steps != message.end()) {
      if (!steps->is_number_integer() || steps->get<std::int64_t>() < 1 || steps->get<std::int64_t>() > 1000000) {
        return std::string("steps = " + steps->dump() + ": not an integer in 1..1000000");
      }
      request.steps = steps->get<std::uint32_t>();
    }
  } else if (name == "rtf") {
    request.kind = ClockRequest::Kind::kRealtimeFactor;
    const auto value = message.find("value");
    if (value == message.end() || !value->is_number() || !std::isfinite(value->get<double>()) ||
        value->get<double>() < 0.0 || value->get<double>() > 1000.0) {
      return std::string("value = ") + (value == message.end() ? "(missing)" : value->dump()) +
             ": not a number in 0..1000";
    }
    request.realtime_factor = value->get<double>();
  } else {
    return "cmd = " + cmd->dump() + ": unknown (pause, resume, step, stop, rtf)";
  }
  return request;
}

}  // namespace climbsim::viewer
