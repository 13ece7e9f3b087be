#include "run_description.hpp"

#include "climbsim/robot/robot_description.hpp"
#include "climbsim/robot/robot_geometry.hpp"
#include "robot_shape.hpp"

namespace climbsim::viewer {

double downforceSetpoint(const Scenario& scenario, double robot_desired_n) {
  if (scenario.controller.kind == Scenario::ControllerKind::kReference && scenario.controller.downforce_n > 0.0) {
    return scenario.controller.downforce_n;
  }
  return robot_desired_n;
}

nlohmann::json helloJson(const std::string& mode, const Scenario& scenario) {
  const RobotDescription robot = loadRobotDescription(scenario.robotPath());
  const RobotGeometry geometry = computeGeometry(robot);
  return {{"type", "hello"},
          {"mode", mode},
          {"robot", robotShapeJson(robot, geometry)},
          {"scenario",
           {{"name", scenario.name},
            {"duration_s", scenario.duration_s},
            {"step_s", static_cast<double>(scenario.step_ns) * 1e-9},
            {"setpoint_n", downforceSetpoint(scenario, robot.adhesion.desired_downforce_n)},
            {"start", {{"x_m", scenario.start.x_m}, {"y_m", scenario.start.y_m}, {"yaw_deg", scenario.start.yaw_deg}}},
            {"wall", toString(scenario.wall.kind)}}}};
}

}  // namespace climbsim::viewer
