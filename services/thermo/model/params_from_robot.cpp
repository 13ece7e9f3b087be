#include "params_from_robot.hpp"

#include <cmath>
#include <sstream>

#include "climbsim/errors.hpp"

namespace climbsim::thermo {
namespace {

// Chambers 0..N-1 and the reservoir N keep their index; the ambient has its own sentinel.
int thermoVolume(VolumeId id) { return id == climbsim::kAmbient ? thermo::kAmbient : id; }

std::string formatNumber(double value) {
  std::ostringstream os;
  os << value;
  return os.str();
}

}  // namespace

std::vector<PlantFault> plantFaultsFromScenario(const std::vector<Scenario::Fault>& faults, const std::string& source,
                                                const ThermoParams& params) {
  const int chambers = params.chamberCount();
  const std::size_t engine_count = params.engines.size();
  std::vector<PlantFault> out;
  for (std::size_t i = 0; i < faults.size(); ++i) {
    const auto& f = faults[i];
    const std::string key = source + ": faults[" + std::to_string(i) + "]";
    if (f.kind == Scenario::FaultKind::kValveStuck && params.valveCount() == 0) {
      throw ConfigError(key + ".kind = valve_stuck: the robot has no valves (no reservoir)");
    }
    if (f.kind == Scenario::FaultKind::kValveStuck && (f.chamber < 1 || f.chamber > chambers)) {
      throw ConfigError(key + ".chamber = " + std::to_string(f.chamber) + ": chambers are 1.." +
                        std::to_string(chambers));
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
  ThermoParams p;
  p.gas.ambient_pressure_pa = description.gas.ambient_pressure_pa;
  p.gas.kappa = description.gas.kappa;
  p.gas.gas_constant_jpkgk = description.gas.r_air_jpkgk;
  p.gas.temperature_k = description.gas.temperature_k;
  p.gas.orifice_density_kgpm3 = description.gas.rho_kgpm3;

  const std::size_t n = geometry.chambers.size();
  p.chamber_volume_m3.resize(n);
  p.chamber_area_m2.resize(n);
  p.p_RobotChamber_m.resize(n);
  for (const auto& chamber : geometry.chambers) {
    const auto i = static_cast<std::size_t>(chamber.id);
    p.chamber_volume_m3.at(i) = chamber.volume_m3;
    p.chamber_area_m2.at(i) = chamber.area_m2;
    p.p_RobotChamber_m.at(i) = {chamber.p_RobotCentroid.x_m, chamber.p_RobotCentroid.y_m};
  }
  p.has_reservoir = geometry.has_reservoir;
  p.reservoir_volume_m3 = geometry.reservoir_volume_m3;

  for (const auto& segment : geometry.segments) {
    p.segments.push_back({thermoVolume(segment.volume_a), thermoVolume(segment.volume_b)});
  }
  const SuctionEngineParams engine{description.engines.dp_max_pa, description.engines.flow_max_m3ps,
                                   description.engines.speed_lag_s};
  p.engines.assign(static_cast<std::size_t>(description.engines.count), engine);
  if (!geometry.has_reservoir) {
    if (description.engines.chambers.size() != p.engines.size()) {
      throw ConfigError("robot " + description.name + ": engines.chambers names " +
                        std::to_string(description.engines.chambers.size()) + " chambers for " +
                        std::to_string(p.engines.size()) + " engines (one each without a reservoir)");
    }
    for (std::size_t e = 0; e < p.engines.size(); ++e) p.engines[e].chamber = description.engines.chambers[e] - 1;
  }
  if (geometry.has_reservoir) {
    p.valve = ValveParams{description.valves.max_area_m2, description.valves.discharge_coefficient,
                          description.valves.full_stroke_s, description.valves.command_delay_s};
  }
  p.validate();
  return p;
}

}  // namespace climbsim::thermo
