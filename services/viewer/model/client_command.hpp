#pragma once
/// @file
/// What a browser may ask of the viewer over the WebSocket: clock controls. Anything else is
/// garbage: the viewer closes that client's connection and the run goes on.

#include <cstdint>
#include <string>
#include <variant>

namespace climbsim::viewer {

/// A clock control (the page's run panel), as ClockControl carries it.
struct ClockRequest {
  enum class Kind { kPause, kResume, kStep, kStop, kRealtimeFactor };
  Kind kind = Kind::kPause;
  std::uint32_t steps = 1;        ///< kStep: 1..1000000
  double realtime_factor = 0.0;   ///< kRealtimeFactor: 0 (as fast as possible) .. 1000
};

/// Parses one WebSocket text message: {"cmd": "pause"|"resume"|"stop"} or
/// {"cmd": "step", "steps": N} or {"cmd": "rtf", "value": X}. Returns the request, or an
/// error text naming what is wrong (not JSON, unknown cmd, missing or out-of-range value).
std::variant<ClockRequest, std::string> parseClientMessage(const std::string& text);

}  // namespace climbsim::viewer
