#include "configure.hpp"

#include <cmath>

#include "climbsim/errors.hpp"
#include "recorded_commands_file.hpp"

namespace climbsim::controller {

ControllerParams configureController(const ScenarioAndRobot& run) {
  if (!run.scenario) throw ConfigError("the controller needs a scenario (--scenario FILE)");
  ControllerParams params = controllerParams(*run.scenario, run.robot, run.geometry);
  if (params.kind == Scenario::ControllerKind::kRecorded) {
    params.recorded = readRecordedCommands(run.scenario->controller.commands_file, run.geometry, params.engine_count,
                                           std::llround(run.scenario->duration_s * 1e9));
  }
  return params;
}

}  // namespace climbsim::controller
