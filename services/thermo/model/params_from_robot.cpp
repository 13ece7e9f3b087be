#include "params_from_robot.hpp"

#include "climbsim/errors.hpp"

namespace climbsim::thermo {
namespace {

int thermoVolume(const RobotGeometry& geometry, VolumeId id) {
  if (id == climbsim::kAmbient) return thermo::kAmbient;
  if (id == geometry.reservoir()) return kReservoir;
  return id;  // ring chambers 0..N-1 and the centre N = kNumChambers - 1 keep their index
}

}  // namespace

ThermoParams thermoParamsFromRobot(const RobotDescription& description, const RobotGeometry& geometry) {
  if (geometry.outer_count != kNumChambers - 1 ||
      geometry.chambers.size() != static_cast<std::size_t>(kNumChambers)) {
    throw ConfigError("robot " + description.name + ": chambers.outer_count = " +
                      std::to_string(geometry.outer_count) + " (the thermo model has " +
                      std::to_string(kNumChambers - 1) + " ring chambers)");
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
