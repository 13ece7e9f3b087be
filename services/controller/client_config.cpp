#include "client_config.hpp"

namespace climbsim::controller {

nlohmann::json clientConfigJson(const Scenario& scenario, const ControllerParams& config) {
  nlohmann::json drive = nlohmann::json::array();
  for (const auto& d : config.drive) {
    drive.push_back({{"t_s", d.t_s}, {"vx_mps", d.vx_mps}, {"vy_mps", d.vy_mps}, {"wz_radps", d.wz_radps}});
  }
  const AdhesionControllerParams& p = config.reference;
  nlohmann::json centroids = nlohmann::json::array();
  for (const auto& c : p.p_RobotChamber_m) centroids.push_back({c[0], c[1]});
  const EngineControllerParams& e = config.engine_reference;
  nlohmann::json engine_centroids = nlohmann::json::array();
  for (const auto& c : e.p_RobotChamber_m) engine_centroids.push_back({c[0], c[1]});
  return {
      {"scenario", scenario.name},
      {"source", scenario.source},
      {"controller", toString(config.kind)},
      {"fixed_valves", config.fixed_valves},
      {"engine_count", config.engine_count},
      {"chamber_count", config.chamber_count},
      {"has_reservoir", config.has_reservoir},
      {"drive", drive},
      {"reference",
       {{"ambient_pressure_pa", p.ambient_pressure_pa},
        {"chamber_area_m2", p.chamber_area_m2},
        {"p_RobotChamber_m", centroids},
        {"desired_downforce_n", p.desired_downforce_n},
        {"balance", p.balance},
        {"max_suction_pa", p.max_suction_pa},
        {"valve_full_stroke_s", p.valve_full_stroke_s},
        {"valve_command_delay_s", p.valve_command_delay_s},
        {"fan_max_suction_pa", p.fan_max_suction_pa}}},
      {"engine_reference",
       {{"ambient_pressure_pa", e.ambient_pressure_pa},
        {"chamber_area_m2", e.chamber_area_m2},
        {"p_RobotChamber_m", engine_centroids},
        {"engine_chamber", e.engine_chamber},
        {"desired_downforce_n", e.desired_downforce_n},
        {"balance", e.balance},
        {"max_suction_pa", e.max_suction_pa},
        {"engine_integral_s", e.engine_integral_s},
        {"engine_prop", e.engine_prop},
        {"balance_tau_s", e.balance_tau_s},
        {"max_trim", e.max_trim}}},
  };
}

}  // namespace climbsim::controller
