#include "configure.hpp"

#include "params_from_robot.hpp"

namespace climbsim::thermo {

ThermoSetup configureThermo(const ScenarioAndRobot& run, const ThermoOverrides& overrides) {
  ThermoSetup setup;
  setup.inputs = parseThermoNodeInputs(overrides.inputs);
  setup.params = thermoParamsFromRobot(run.robot, run.geometry);
  if (run.scenario) {
    setup.params.faults =
        plantFaultsFromScenario(run.scenario->faults, run.scenario->source, setup.params);
  }
  setup.segment_names = segmentNames(run.geometry);
  setup.basic_leak_area_m2 = basicLeakAreas(run.robot, run.geometry);
  return setup;
}

}  // namespace climbsim::thermo
