#include "thermo_translate.hpp"

#include "climbsim/robot/robot_description.hpp"

#include <stdexcept>

namespace climbsim::thermo {

std::vector<double> valveCommandFromIdl(const climbsim::ValveCommand& sample) { return sample.opening(); }

climbsim::ValveCommand valveCommandToIdl(const std::vector<double>& opening) {
  if (opening.size() > static_cast<std::size_t>(kMaxChambers)) {
    throw std::invalid_argument("ValveCommand: " + std::to_string(opening.size()) + " openings (at most " +
                                std::to_string(kMaxChambers) + ")");
  }
  climbsim::ValveCommand sample;
  sample.opening() = opening;
  return sample;
}

std::vector<EngineCommand> engineCommandsFromIdl(const climbsim::EngineCommand& sample) {
  std::vector<EngineCommand> engines;
  for (const auto& e : sample.engines()) engines.push_back(EngineCommand{e.on(), e.speed()});
  return engines;
}

climbsim::EngineCommand engineCommandToIdl(const std::vector<EngineCommand>& engines) {
  if (engines.size() > static_cast<std::size_t>(kMaxEngines)) {
    throw std::invalid_argument("EngineCommand: " + std::to_string(engines.size()) + " engines (at most " +
                                std::to_string(kMaxEngines) + ")");
  }
  climbsim::EngineCommand sample;
  for (const auto& e : engines) {
    climbsim::EngineSetting setting;
    setting.on(e.on);
    setting.speed(e.speed);
    sample.engines().push_back(setting);
  }
  return sample;
}

climbsim::Leakage leakageToIdl(const std::vector<std::string>& names, const std::vector<double>& leak_area_m2,
                               const std::vector<double>& mean_gap_m, const std::vector<std::size_t>& indices) {
  if (indices.size() > static_cast<std::size_t>(kMaxSegments)) {
    throw std::invalid_argument("Leakage: " + std::to_string(indices.size()) + " segments (at most " +
                                std::to_string(kMaxSegments) + ")");
  }
  climbsim::Leakage sample;
  for (const std::size_t i : indices) {
    climbsim::LeakageSegment segment;
    segment.segment(names.at(i));
    segment.leak_area_m2(leak_area_m2.at(i));
    segment.mean_gap_m(mean_gap_m.at(i));
    sample.segments().push_back(segment);
  }
  return sample;
}

climbsim::ChamberState chamberStateToIdl(const ThermoOutputs& outputs) {
  if (outputs.pressure_pa.size() > static_cast<std::size_t>(kMaxChambers + 1) ||
      outputs.valve_opening.size() > static_cast<std::size_t>(kMaxChambers) ||
      outputs.engine_speed.size() > static_cast<std::size_t>(kMaxEngines) ||
      outputs.segment_mass_flow_kgps.size() > static_cast<std::size_t>(kMaxSegments)) {
    throw std::invalid_argument(
        "ChamberState: " + std::to_string(outputs.pressure_pa.size()) + " pressures, " +
        std::to_string(outputs.valve_opening.size()) + " valves, " + std::to_string(outputs.engine_speed.size()) +
        " engines, " + std::to_string(outputs.segment_mass_flow_kgps.size()) + " segments (at most " +
        std::to_string(kMaxChambers + 1) + ", " + std::to_string(kMaxChambers) + ", " + std::to_string(kMaxEngines) +
        " and " + std::to_string(kMaxSegments) + ")");
  }
  climbsim::ChamberState sample;
  sample.pressure_pa() = outputs.pressure_pa;
  sample.valve_opening() = outputs.valve_opening;
  sample.engine_speed() = outputs.engine_speed;
  sample.segment_mass_flow_kgps() = outputs.segment_mass_flow_kgps;
  return sample;
}

climbsim::AdhesionForce adhesionForceToIdl(const ThermoOutputs& outputs) {
  climbsim::AdhesionForce sample;
  sample.downforce_n(outputs.downforce_n);
  sample.pf_x_m(outputs.p_RobotPF_m[0]);
  sample.pf_y_m(outputs.p_RobotPF_m[1]);
  return sample;
}

ThermoOutputs outputsFromIdl(const climbsim::ChamberState& state, const climbsim::AdhesionForce& force) {
  ThermoOutputs out;
  out.pressure_pa = state.pressure_pa();
  out.valve_opening = state.valve_opening();
  out.engine_speed = state.engine_speed();
  out.segment_mass_flow_kgps = state.segment_mass_flow_kgps();
  out.downforce_n = force.downforce_n();
  out.p_RobotPF_m = {force.pf_x_m(), force.pf_y_m()};
  return out;
}

}  // namespace climbsim::thermo
