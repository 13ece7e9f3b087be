#include "params_from_robot.hpp"

#include <cmath>
#include <sstream>

#include "climbsim/errors.hpp"

namespace climbsim::thermo {
namespace {

int thermoVolume(const RobotGeometry& geometry, VolumeId id) {
  if (id == climbsim::kAmbient) return thermo::kAmbient;
  if (id == geometry.reservoir()) return kReservoir;
  return id;  // ring chambers 0..N-1 and the centre N = kNumChambers - 1 keep their index
}

std::string formatNumber(double value) {
  std::ostringstream os;
  os << value;
  return os.str();
}

}  // namespace

std::vector<PlantFault> plantFaultsFromScenario(const std::vector<Scenario::Fault>& faults, const std::string& source,
                                                std::size_t engine_count) {
  std::vector<PlantFault> out;
  for (std::size_t i = 0; i < faults.size(); ++i) {
    const auto& f = faults[i];
    const std::string key = source + ": faults[" + std::to_string(i) + "]";
    if (f.kind == Scenario::FaultKind::kValveStuck && (f.chamber < 1 || f.chamber > kNumChambers)) {
      throw ConfigError(key + ".chamber = " + std::to_string(f.chamber) + ": chambers are 1.." +
                        std::to_string(kNumChambers));
    }
    if (f.kind == Scenario::FaultKind::kValveStuck && !(f.opening >= 0.0 && f.opening <= 1.0)) {
      throw ConfigError(key + ".opening = " + formatNumber(f.opening) + ": must be in [0, 1]");
    }
    const auto engines = static_cast<int>(engine_count);
    if (f.kind == Scenario::FaultKind::kEngineFailure && (f.engine < 1 || f.engine > engines)) {
      throw ConfigError(key + ".engine = " + std::to_string(f.engine) + ": the robot has " + std::to_string(engines) +
                        " engine(s), 1.." + std::to_string(engines));
    }
    if (!std::isfinite(f.t_s)) throw ConfigError(key + ".t_s = " + formatNumber(f.t_s) + ": must be finite");
    PlantFault fault;
    fault.kind = f.kind == Scenario::FaultKind::kValveStuck ? PlantFault::Kind::kValveStuck
                                                            : PlantFault::Kind::kEngineFailure;
    fault.t_ns = static_cast<std::int64_t>(std::llround(f.t_s * 1e9));
    fault.chamber = f.chamber;
    fault.opening = f.opening;
    fault.engine = f.engine;
    out.push_back(fault);
  }
  return out;
}

ThermoParams thermoParamsFromRobot(const RobotDescription& description, const RobotGeometry& geometry) {
  if (geometry.chambers.size() != static_cast<std::size_t>(kNumChambers) || !geometry.has_reservoir) {
    throw ConfigError("robot " + description.name + ": " + std::to_string(geometry.chambers.size()) + " chambers" +
                      (geometry.has_reservoir ? "" : " without a reservoir") + " (the thermo model has " +
                      std::to_string(kNumChambers) + " chambers and a reservoir)");
  }
  ThermoParams p;
  p.gas.ambient_pressure_pa = description.gas.ambient_pressure_pa;
  p.gas.kappa = description.gas.kappa;
  p.gas.gas_constant_jpkgk = description.gas.r_air_jpkgk;
  p.gas.temperature_k = description.gas.temperature_k;
  p.gas.orifice_density_kgpm3 = description.gas.rho_kgpm3;

  for (const auto& chamber : geometry.chambers) {
    const auto i = static_cast<std::size_t>(chamber.id);
    p.chamber_volume_m3[i] = chamber.volume_m3;
    p.chamber_area_m2[i] = chamber.area_m2;
    p.p_RobotChamber_m[i] = {chamber.p_RobotCentroid.x_m, chamber.p_RobotCentroid.y_m};
  }
  p.reservoir_volume_m3 = geometry.reservoir_volume_m3;

  for (const auto& segment : geometry.segments) {
    p.segments.push_back({thermoVolume(geometry, segment.volume_a), thermoVolume(geometry, segment.volume_b)});
  }
  p.engines.assign(static_cast<std::size_t>(description.engines.count),
                   SuctionEngineParams{description.engines.dp_max_pa, description.engines.flow_max_m3ps,
                                       description.engines.speed_lag_s});
  p.valve = ValveParams{description.valves.max_area_m2, description.valves.discharge_coefficient,
                        description.valves.full_stroke_s, description.valves.command_delay_s};
  p.validate();
  return p;
}

}  // namespace climbsim::thermo
