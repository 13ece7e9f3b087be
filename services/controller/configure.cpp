#include "configure.hpp"

#include "climbsim/errors.hpp"

namespace climbsim::controller {

ControllerParams configureController(const ScenarioAndRobot& run) {
  if (!run.scenario) throw ConfigError("the controller needs a scenario (--scenario FILE)");
  return controllerParams(*run.scenario, run.robot, run.geometry);
}

}  // namespace climbsim::controller
