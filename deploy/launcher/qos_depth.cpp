#include "qos_depth.hpp"

#include <tinyxml2.h>

#include <algorithm>
#include <limits>

#include "climbsim/errors.hpp"

namespace climbsim::launcher {

namespace {
/// KEEP_LAST depth of the profile element (KEEP_ALL: unlimited); throws if absent.
int depthOf(const tinyxml2::XMLElement* profile, const std::string& file, const std::string& name) {
  const auto* history = profile->FirstChildElement("topic");
  history = history ? history->FirstChildElement("historyQos") : nullptr;
  const auto* kind = history ? history->FirstChildElement("kind") : nullptr;
  if (kind && kind->GetText() && std::string(kind->GetText()) == "KEEP_ALL") {
    return std::numeric_limits<int>::max();
  }
  const auto* depth = history ? history->FirstChildElement("depth") : nullptr;
  int value = 0;
  if (!depth || depth->QueryIntText(&value) != tinyxml2::XML_SUCCESS || value < 1) {
    throw ConfigError(file + ": profile '" + name + "': no KEEP_LAST depth >= 1");
  }
  return value;
}
}  // namespace

int stepDataQueueDepth(const std::string& qos_file) {
  tinyxml2::XMLDocument doc;
  if (doc.LoadFile(qos_file.c_str()) != tinyxml2::XML_SUCCESS) {
    throw ConfigError(qos_file + ": cannot read it as XML (" + std::string(doc.ErrorStr()) + ")");
  }
  const auto* root = doc.RootElement();
  const auto* profiles = root ? root->FirstChildElement("profiles") : nullptr;
  int depth = std::numeric_limits<int>::max();
  int found = 0;
  for (const char* tag : {"data_writer", "data_reader"}) {
    const std::string name = std::string("climbsim.step_data.") + (tag[5] == 'w' ? "writer" : "reader");
    for (auto* e = profiles ? profiles->FirstChildElement(tag) : nullptr; e; e = e->NextSiblingElement(tag)) {
      if (e->Attribute("profile_name", name.c_str())) {
        depth = std::min(depth, depthOf(e, qos_file, name));
        ++found;
      }
    }
  }
  if (found != 2) {
    throw ConfigError(qos_file + ": no writer and reader profiles 'climbsim.step_data'");
  }
  return depth;
}

void checkWindowFitsQueues(std::uint32_t window_steps, const std::string& qos_file) {
  if (window_steps < 1) {
    throw ConfigError("clock.window_steps = 0: it must be >= 1 (1 = one grant per step)");
  }
  const int depth = stepDataQueueDepth(qos_file);
  const long long most = std::max(1LL, static_cast<long long>(depth) - 2);
  if (static_cast<long long>(window_steps) > most) {
    throw ConfigError("clock.window_steps (--window-steps) = " + std::to_string(window_steps) + ": above " + std::to_string(most) +
                      ", the most the step-data queues hold (history depth " + std::to_string(depth) +
                      " of QoS profile 'climbsim.step_data' in " + qos_file + "); lower the window or deepen the queues");
  }
}

}  // namespace climbsim::launcher
