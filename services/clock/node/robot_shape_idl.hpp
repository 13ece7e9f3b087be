#pragma once
/// @file
/// The run's robot as RunStart carries it (idl/clock.idl RobotShape): what every participant and
/// client sizes itself from.

#include <string>

#include "clock.h"

namespace climbsim::clock {

/// The robot of `robot_file` (a path, or a shipped robot's name), validated; ConfigError
/// listing the file's problems otherwise.
climbsim::RobotShape robotShapeFromFile(const std::string& robot_file);

}  // namespace climbsim::clock
