#pragma once
/// @file
/// climbsim-thermo's configuration (docs/design.md#configuration): the run's scenario and the
/// robot to the thermo model's parameters (plant faults included) and what its node needs.
/// climbsim-thermo's main and climbsim solo both call configureThermo.

#include <string>
#include <vector>

#include "climbsim/scenario_and_robot.hpp"
#include "node/thermo_node.hpp"
#include "thermo_params.hpp"

namespace climbsim::thermo {

/// climbsim-thermo's options besides --scenario/--set/--robot.
struct ThermoOverrides {
  std::string inputs = "leakage,valves,engines";  ///< --inputs: parseThermoNodeInputs
};

/// Everything climbsim-thermo's node is made of (ThermoNode's arguments).
struct ThermoSetup {
  ThermoParams params;                      ///< of the robot; faults: the scenario's plant faults
  std::vector<std::string> segment_names;   ///< the sealing segments, geometry order
  std::vector<double> basic_leak_area_m2;   ///< l_i L_basic per segment, geometry order [m^2]
  ThermoNodeInputs inputs;                  ///< the topics read
};

/// The thermo setup of `run`: thermoParamsFromRobot, the scenario's faults
/// (plantFaultsFromScenario; none without a scenario). ConfigErrors as those give them, and
/// for a bad --inputs.
ThermoSetup configureThermo(const ScenarioAndRobot& run, const ThermoOverrides& overrides = {});

}  // namespace climbsim::thermo
