#include "process_watch.hpp"

#include <unistd.h>

#include <fstream>

#include "climbsim/names.hpp"

namespace climbsim::clock {

char processState(std::uint32_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string text;
  std::getline(in, text);
  const auto paren = text.rfind(')');  // the command name may hold spaces and parentheses
  if (paren == std::string::npos || paren + 2 >= text.size()) return 0;
  return text[paren + 2];
}

bool processEnded(char state) { return state == 0 || state == 'Z' || state == 'X'; }

bool isThisHostName(const std::string& host) {
  char this_host[256] = {};
  ::gethostname(this_host, sizeof this_host - 1);
  return host == std::string(this_host).substr(0, kMaxNameLength);
}

bool onThisHost(const ParticipantId& theirs, const ParticipantId& ours, const std::string& host, std::uint32_t pid) {
  if (pid == 0 || host.empty() || !isThisHostName(host)) return false;
  // Fast DDS's GUID prefix: vendor (0-1), host id (2-3), pid's low 16 bits (4-5), random (6-7).
  if (theirs.value[0] != ours.value[0] || theirs.value[1] != ours.value[1]) return false;
  if (theirs.value[2] != ours.value[2] || theirs.value[3] != ours.value[3]) return false;
  if (theirs.value[4] != static_cast<std::uint8_t>(pid & 0xFF) ||
      theirs.value[5] != static_cast<std::uint8_t>((pid >> 8) & 0xFF)) {
    return false;
  }
  return !processEnded(processState(pid));
}

std::vector<std::pair<std::string, std::uint32_t>> ProcessWatch::stoppedFor(
    std::chrono::steady_clock::duration limit) {
  const auto now = std::chrono::steady_clock::now();
  std::vector<std::pair<std::string, std::uint32_t>> out;
  for (const auto& [name, pid] : pids_) {
    const char state = processState(pid);
    if (state != 'T' && state != 't') {
      stopped_since_.erase(name);
      continue;
    }
    const auto since = stopped_since_.emplace(name, now).first->second;
    if (now - since >= limit && named_stopped_.insert(name).second) out.emplace_back(name, pid);
  }
  return out;
}

std::vector<std::pair<std::string, std::uint32_t>> ProcessWatch::ended() {
  std::vector<std::pair<std::string, std::uint32_t>> out;
  for (auto it = pids_.begin(); it != pids_.end();) {
    if (processEnded(processState(it->second))) {
      out.emplace_back(it->first, it->second);
      it = pids_.erase(it);
    } else {
      ++it;
    }
  }
  return out;
}

}  // namespace climbsim::clock
