#include "viewer_port.hpp"

#include <algorithm>
#include <filesystem>

namespace climbsim::launcher {

int letViewersFindAFreePort(ComposeFile& compose) {
  int changed = 0;
  for (auto& service : compose.services) {
    auto& command = service.command;
    if (command.empty() || std::filesystem::path(command.front()).filename() != "climbsim-viewer") continue;
    std::string port = std::to_string(kDefaultViewerPort);
    bool has_tries = false;
    for (std::size_t i = 1; i < command.size(); ++i) {
      if (command[i] == "--port" && i + 1 < command.size()) port = command[i + 1];
      if (command[i].rfind("--port=", 0) == 0) port = command[i].substr(7);
      has_tries = has_tries || command[i] == "--port-tries" || command[i].rfind("--port-tries=", 0) == 0;
    }
    if (has_tries || port != std::to_string(kDefaultViewerPort)) continue;
    command.insert(command.end(), {"--port-tries", std::to_string(kViewerPortTries)});
    ++changed;
  }
  return changed;
}

std::optional<std::string> viewerAddressIn(std::string_view line) {
  constexpr std::string_view kOpen = "open http://";
  const auto at = line.find(kOpen);
  if (at == std::string_view::npos) return std::nullopt;
  const auto begin = at + 5;  // "http://..."
  const auto end = std::min(line.find(' ', begin), line.size());
  return std::string(line.substr(begin, end - begin));
}

}  // namespace climbsim::launcher
