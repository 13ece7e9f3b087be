#pragma once
/// @file
/// The command line every lockstep service's main shares (docs/design.md#configuration): the
/// participant's options (ParticipantOptions), --scenario FILE, --set KEY=VALUE and, for a
/// service that also runs without a scenario, --robot FILE. A main adds its own options to
/// `app`, runs, loads the scenario and robot (load) and hands them to its configure function.

#include <CLI/CLI.hpp>

#include <functional>
#include <string>
#include <vector>

#include "climbsim/lockstep_participant.hpp"
#include "climbsim/scenario_and_robot.hpp"

namespace climbsim {

class ServiceCommandLine {
 public:
  /// `description`: --help's title; `scenario_help`: what the service takes from the scenario;
  /// `set_example`: a KEY=VALUE for --set's help. `default_scenario`: the scenario without
  /// --scenario ("": none, and --set needs --scenario).
  ServiceCommandLine(const std::string& description, const std::string& scenario_help,
                     const std::string& set_example, const std::string& default_scenario = "");

  /// Adds --robot (refused with --scenario, whose robot counts).
  CLI::Option* addRobotOption(const std::string& help = "robot description (deploy/robots/*.yaml)");

  /// guardedMain: parses the command line and runs `body` as `process_name`.
  int run(int argc, char** argv, const std::string& process_name, const std::function<int()>& body);

  /// The scenario (with its overrides) and the robot of the command line (loadScenarioAndRobot).
  ScenarioAndRobot load() const;

  CLI::App app;
  ParticipantOptions participant;
  std::string scenario_file;           ///< --scenario
  std::vector<std::string> overrides;  ///< --set
  std::string robot_file;              ///< --robot ("": the default robot)
  CLI::Option* scenario_option = nullptr;
};

/// The build directory of this build: where a scenario's "$BUILD/" files are.
const std::string& thisBuildDir();

}  // namespace climbsim
