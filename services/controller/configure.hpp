#pragma once
/// @file
/// climbsim-controller's configuration (docs/design.md#configuration): the run's scenario
/// (controller section, drive schedule) and the robot to the command model's parameters.
/// climbsim-controller's main (and its --print-config for the clients in other languages) and
/// climbsim solo both call configureController.

#include "climbsim/scenario_and_robot.hpp"
#include "command_model.hpp"

namespace climbsim::controller {

/// controllerParams of run's scenario and robot, with a recorded controller's commands read from
/// its controller.commands (readRecordedCommands). ConfigError if `run` has no scenario (the
/// controller's commands are the scenario's), and as controllerParams and readRecordedCommands
/// give them.
ControllerParams configureController(const ScenarioAndRobot& run);

}  // namespace climbsim::controller
