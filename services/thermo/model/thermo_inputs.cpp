#include <cmath>
#include <sstream>
#include <string>

#include "thermo_types.hpp"

namespace climbsim::thermo {
namespace {

std::string describe(const std::string& key, double value, const char* rule) {
  std::ostringstream os;
  os << "thermo input: " << key << " = " << value << " (must be " << rule << ")";
  return os.str();
}

}  // namespace

std::string validateInputs(const ThermoParams& params, const ThermoInputs& inputs) {
  if (inputs.leak_area_m2.size() != params.segments.size()) {
    return "thermo input: leak_area_m2 has " + std::to_string(inputs.leak_area_m2.size()) +
           " entries, the robot has " + std::to_string(params.segments.size()) + " sealing segments";
  }
  for (std::size_t s = 0; s < inputs.leak_area_m2.size(); ++s) {
    const double a = inputs.leak_area_m2[s];
    if (!std::isfinite(a) || a < 0.0) return describe("leak_area_m2[" + std::to_string(s) + "]", a, "finite and >= 0");
  }
  const auto valves = static_cast<std::size_t>(params.valveCount());
  if (inputs.valve_command.size() != valves) {
    return "thermo input: valve_command has " + std::to_string(inputs.valve_command.size()) +
           " entries, the robot has " + std::to_string(valves) + " valves" +
           (params.has_reservoir ? " (one per chamber)" : " (no reservoir: none)");
  }
  for (std::size_t c = 0; c < inputs.valve_command.size(); ++c) {
    const double v = inputs.valve_command[c];
    if (!(v >= 0.0 && v <= 1.0)) return describe("valve_command[" + std::to_string(c) + "]", v, "in [0, 1]");
  }
  if (inputs.engines.size() != params.engines.size()) {
    return "thermo input: engines has " + std::to_string(inputs.engines.size()) + " entries, the robot has " +
           std::to_string(params.engines.size()) + " engines";
  }
  for (std::size_t e = 0; e < inputs.engines.size(); ++e) {
    const double v = inputs.engines[e].speed;
    if (!(v >= 0.0 && v <= 1.0)) return describe("engines[" + std::to_string(e) + "].speed", v, "in [0, 1]");
  }
  return {};
}

}  // namespace climbsim::thermo
