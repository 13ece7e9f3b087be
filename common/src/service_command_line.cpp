#include "climbsim/service_command_line.hpp"

#include "climbsim/main_guard.hpp"

#ifndef CLIMBSIM_BUILD_DIR
#error "CLIMBSIM_BUILD_DIR must name the build directory (a scenario's $BUILD/)"
#endif

namespace climbsim {

ServiceCommandLine::ServiceCommandLine(const std::string& description, const std::string& scenario_help,
                                       const std::string& set_example, const std::string& default_scenario)
    : app(description), scenario_file(default_scenario) {
  participant.addOptions(app);
  scenario_option = app.add_option("--scenario", scenario_file, scenario_help);
  auto* set = app.add_option("--set", overrides, "override a scenario key, e.g. --set " + set_example + " (repeatable)");
  if (default_scenario.empty()) set->needs(scenario_option);
}

CLI::Option* ServiceCommandLine::addRobotOption(const std::string& help) {
  return app.add_option("--robot", robot_file, help)->excludes(scenario_option);
}

int ServiceCommandLine::run(int argc, char** argv, const std::string& process_name, const std::function<int()>& body) {
  return guardedMain(app, argc, argv, process_name, body);
}

ScenarioAndRobot ServiceCommandLine::load() const { return loadScenarioAndRobot(scenario_file, overrides, robot_file); }

const std::string& thisBuildDir() {
  static const std::string dir = CLIMBSIM_BUILD_DIR;
  return dir;
}

}  // namespace climbsim
