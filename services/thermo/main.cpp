/// climbsim-thermo: the airflow and downforce service (docs/design.md#airflow-and-downforce). Reads
/// Leakage (merged from every sealing shard), ValveCommand and EngineCommand; writes ChamberState
/// and AdhesionForce every due step. With --scenario the robot and the plant faults (stuck
/// valve, failed engine) come from the scenario file (configure.hpp).

#include <spdlog/spdlog.h>

#include "climbsim/logging.hpp"
#include "climbsim/service_command_line.hpp"
#include "configure.hpp"
#include "node/thermo_participant.hpp"

int main(int argc, char** argv) {
  using namespace climbsim;
  ServiceCommandLine cli("climbsim-thermo: chambers, reservoir, suction engines, valves and downforce",
                         "scenario file (deploy/scenarios/*.yaml): the robot and the plant faults (valve_stuck, "
                         "engine_failure) come from it; excludes --robot",
                         "faults[0].t_s=3");
  thermo::ThermoOverrides o;
  cli.addRobotOption();
  cli.app.add_option("--inputs", o.inputs,
                     "inputs to read, comma-separated from leakage,valves,engines, or none; "
                     "an absent one keeps its default (basic leakage, valves closed, engines off)");
  return cli.run(argc, argv, "thermo", [&]() -> int {
    initLogging(cli.participant.name);
    const ScenarioAndRobot run = cli.load();
    thermo::ThermoSetup setup = thermo::configureThermo(run, o);
    thermo::ThermoNode node(std::move(setup.params), std::move(setup.segment_names),
                            std::move(setup.basic_leak_area_m2));
    if (run.scenario) spdlog::info("thermo: scenario {}: {} plant fault(s)", run.scenario->name, run.scenario->faults.size());
    return thermo::runThermoParticipant(cli.participant, setup.inputs, node);
  });
}
