#include "configure.hpp"

#include "climbsim/scenario.hpp"
#include "run_description.hpp"

namespace climbsim::viewer {

std::string helloText(const std::string& mode, const std::string& scenario_file) {
  return scenario_file.empty() ? std::string() : helloJson(mode, loadScenario(scenario_file)).dump();
}

}  // namespace climbsim::viewer
