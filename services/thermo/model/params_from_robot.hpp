#pragma once
/// @file
/// The thermo model's parameters from the robot description and its geometry, so that
/// nothing of the robot is typed in twice (deploy/robots/*.yaml is the only source).

#include <string>
#include <vector>

#include "climbsim/robot/robot_description.hpp"
#include "climbsim/robot/robot_geometry.hpp"
#include "climbsim/scenario.hpp"
#include "thermo_params.hpp"

namespace climbsim::thermo {

/// ThermoParams of a validated robot of any layout: chamber volumes, suction areas A_i [m^2]
/// and centroids P_i [m, robot frame] from the geometry; the sealing segments in geometry
/// order (volume ids kept: chambers 0..N-1, the reservoir N; the geometry's ambient becomes
/// thermo::kAmbient); the reservoir and its valves where the robot has one, else each engine
/// on the chamber engines.chambers names for it; engines and gas constants from the
/// description. The numerics (laminar threshold, integrator, step control) keep their
/// defaults. ConfigError "robot <name>: ..." where the description does not fit the model.
ThermoParams thermoParamsFromRobot(const RobotDescription& description, const RobotGeometry& geometry);

/// The scenario's plant faults (`faults`) for ThermoParams::faults of a robot with `params`
/// (its chambers, valves and engines): each takes effect at round(t_s * 1e9) ns. ConfigError
/// naming `source` (the scenario file), e.g. "s.yaml: faults[1].engine = 3: the robot has 2
/// engine(s), 1..2", for a stuck valve on a robot without valves, a chamber outside 1..N, an
/// opening outside [0, 1], an engine the robot lacks or a time that is not finite.
std::vector<PlantFault> plantFaultsFromScenario(const std::vector<Scenario::Fault>& faults, const std::string& source,
                                                const ThermoParams& params);

/// The sealing segments' names in the order of ThermoParams::segments (geometry order), and
/// the flat wall's leak areas: common/robot (robot_geometry.hpp), shared with the recorder.
using climbsim::basicLeakAreas;
using climbsim::segmentNames;

}  // namespace climbsim::thermo
