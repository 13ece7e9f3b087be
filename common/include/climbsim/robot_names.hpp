#pragma once
/// @file
/// Shipped robots by name: a scenario's `robot: cromsci` names deploy/robots/cromsci.yaml of
/// this checkout (docs/scenario-files.md), a path names a file.

#include <string>
#include <vector>

namespace climbsim {

/// True if `text` names a shipped robot rather than a file: no '/' and no ".yaml" ending.
bool isShippedRobotName(const std::string& text);
/// The file of the shipped robot `name`: deploy/robots/<name>.yaml of this checkout.
std::string shippedRobotFile(const std::string& name);
/// The robot file a command-line argument (--robot, `robot show`) names: a shipped robot's file
/// for a name (unless a file of that name exists here), else the argument as a path.
std::string robotFileOf(const std::string& argument);
/// The names of the shipped robots (deploy/robots/*.yaml), sorted.
std::vector<std::string> shippedRobotNames();

}  // namespace climbsim
