#include "control_senders.hpp"

#include <algorithm>

#include "climbsim/errors.hpp"
#include "climbsim/names.hpp"

namespace climbsim::clock {

namespace {
std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::size_t begin = 0;
  while (true) {
    const std::size_t end = text.find(separator, begin);
    parts.push_back(text.substr(begin, end == std::string::npos ? std::string::npos : end - begin));
    if (end == std::string::npos) return parts;
    begin = end + 1;
  }
}
}  // namespace

std::vector<ControlSender> parseControlSenders(const std::string& option, const std::string& text) {
  std::vector<ControlSender> senders;
  if (text.empty()) {
    return senders;  // nobody may send ClockControl
  }
  for (const auto& entry : split(text, ',')) {
    ControlSender sender;
    const std::size_t at = entry.find('@');
    sender.name = entry.substr(0, at);
    validateName(option + " entry '" + entry + "'", sender.name);
    if (at != std::string::npos) {
      sender.addresses = split(entry.substr(at + 1), '/');
      if (std::any_of(sender.addresses.begin(), sender.addresses.end(), [](const auto& a) { return a.empty(); })) {
        throw ConfigError(option + " entry '" + entry + "': an empty address (give name@a.b.c.d[/e.f.g.h])");
      }
    }
    senders.push_back(std::move(sender));
  }
  return senders;
}

std::string formatControlSenders(const std::vector<ControlSender>& senders) {
  std::string text;
  for (const auto& sender : senders) {
    text += (text.empty() ? "" : ",") + sender.name;
    for (std::size_t i = 0; i < sender.addresses.size(); ++i) {
      text += (i == 0 ? "@" : "/") + sender.addresses[i];
    }
  }
  return text;
}

std::string controlRefusal(const std::vector<ControlSender>& allowed, const std::string& name,
                           const std::vector<std::string>& addresses) {
  bool named = false;
  for (const auto& sender : allowed) {
    if (sender.name != name) continue;
    named = true;
    if (sender.addresses.empty()) return {};
    for (const auto& address : addresses) {
      if (std::find(sender.addresses.begin(), sender.addresses.end(), address) != sender.addresses.end()) return {};
    }
  }
  std::string list;
  for (const auto& a : addresses) list += (list.empty() ? "" : ", ") + a;
  return named ? "'" + name + "' may send ClockControl only from its listed host, not from " +
                     (list.empty() ? std::string("an unknown address") : list)
               : "'" + name + "' is not among the senders the compose file's clock.control allows (" +
                     formatControlSenders(allowed) + ")";
}

}  // namespace climbsim::clock
