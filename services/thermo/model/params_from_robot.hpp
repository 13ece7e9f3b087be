#pragma once
/// @file
/// The thermo model's parameters from the robot description and its geometry, so that
/// nothing of the robot is typed in twice (deploy/robots/*.yaml is the only source).

#include <string>
#include <vector>

#include "climbsim/robot/robot_description.hpp"
#include "climbsim/robot/robot_geometry.hpp"
#include "thermo_params.hpp"

namespace climbsim::thermo {

/// ThermoParams of a validated robot: chamber volumes, suction areas A_i [m^2] and centroids
/// P_i [m, robot frame] from the geometry; the sealing segments in geometry order (volume ids
/// mapped: ring chambers 0..N-1 and the centre N keep their ids, the geometry's ambient becomes
/// thermo::kAmbient); reservoir, engines, valves and gas constants from the description. The
/// numerics (laminar threshold, integrator, step control) keep their defaults.
/// Throws ConfigError "robot <name>: chambers.outer_count = N (the thermo model has 6 ring
/// chambers)" when the robot does not have kNumChambers - 1 ring chambers.
ThermoParams thermoParamsFromRobot(const RobotDescription& description, const RobotGeometry& geometry);

/// The sealing segments' names in the order of ThermoParams::segments (geometry order), and
/// the flat wall's leak areas: common/robot (robot_geometry.hpp), shared with the recorder.
using climbsim::basicLeakAreas;
using climbsim::segmentNames;

}  // namespace climbsim::thermo
