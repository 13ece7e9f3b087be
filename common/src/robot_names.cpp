#include "climbsim/robot_names.hpp"

#include <algorithm>
#include <filesystem>

#ifndef CLIMBSIM_ROBOTS_DIR
#error "CLIMBSIM_ROBOTS_DIR must name the shipped robots' folder"
#endif

namespace climbsim {

bool isShippedRobotName(const std::string& text) {
  const std::string suffix = ".yaml";
  const bool yaml = text.size() >= suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
  return !text.empty() && text.find('/') == std::string::npos && !yaml;
}

std::string shippedRobotFile(const std::string& name) { return std::string(CLIMBSIM_ROBOTS_DIR) + "/" + name + ".yaml"; }

std::string robotFileOf(const std::string& argument) {
  return isShippedRobotName(argument) && !std::filesystem::exists(argument) ? shippedRobotFile(argument) : argument;
}

std::vector<std::string> shippedRobotNames() {
  std::vector<std::string> names;
  std::error_code ignored;
  for (const auto& entry : std::filesystem::directory_iterator(CLIMBSIM_ROBOTS_DIR, ignored)) {
    if (entry.path().extension() == ".yaml") names.push_back(entry.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace climbsim
