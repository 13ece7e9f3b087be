#include "thermo_params.hpp"

#include <cmath>
#include <sstream>
#include <string>

#include "climbsim/errors.hpp"

namespace climbsim::thermo {
namespace {

[[noreturn]] void reject(const std::string& key, double value, const char* rule) {
  std::ostringstream os;
  os << "thermo: " << key << " = " << value << " (must be " << rule << ")";
  throw ConfigError(os.str());
}

void requirePositive(const std::string& key, double value) {
  if (!std::isfinite(value) || !(value > 0.0)) reject(key, value, "finite and > 0");
}

std::string indexed(const char* key, std::size_t i) { return std::string(key) + "[" + std::to_string(i) + "]"; }

}  // namespace

void ThermoParams::validate() const {
  requirePositive("gas.ambient_pressure_pa", gas.ambient_pressure_pa);
  requirePositive("gas.kappa", gas.kappa);
  requirePositive("gas.gas_constant_jpkgk", gas.gas_constant_jpkgk);
  requirePositive("gas.temperature_k", gas.temperature_k);
  requirePositive("gas.orifice_density_kgpm3", gas.orifice_density_kgpm3);
  const int n = chamberCount();
  if (n < 1 || n > kMaxChambers) reject("chamber_volume_m3.size", n, ("in 1.." + std::to_string(kMaxChambers)).c_str());
  const std::string per_chamber = "equal to the number of chambers, " + std::to_string(n);
  if (chamber_area_m2.size() != chamber_volume_m3.size()) {
    reject("chamber_area_m2.size", static_cast<double>(chamber_area_m2.size()), per_chamber.c_str());
  }
  if (p_RobotChamber_m.size() != chamber_volume_m3.size()) {
    reject("p_RobotChamber_m.size", static_cast<double>(p_RobotChamber_m.size()), per_chamber.c_str());
  }
  for (std::size_t i = 0; i < chamber_volume_m3.size(); ++i) {
    requirePositive(indexed("chamber_volume_m3", i), chamber_volume_m3[i]);
  }
  if (has_reservoir) requirePositive("reservoir_volume_m3", reservoir_volume_m3);
  for (std::size_t i = 0; i < chamber_area_m2.size(); ++i) {
    requirePositive(indexed("chamber_area_m2", i), chamber_area_m2[i]);
    for (std::size_t k = 0; k < 2; ++k) {
      const double v = p_RobotChamber_m[i][k];
      if (!std::isfinite(v)) reject(indexed("p_RobotChamber_m", i) + "[" + std::to_string(k) + "]", v, "finite");
    }
  }
  if (segments.size() > static_cast<std::size_t>(kMaxSegments)) {
    reject("segments.size", static_cast<double>(segments.size()), ("at most " + std::to_string(kMaxSegments)).c_str());
  }
  const int volumes = volumeCount();
  const std::string volume_rule = "a volume, 0.." + std::to_string(volumes - 1) + ", or the ambient, -1";
  for (std::size_t s = 0; s < segments.size(); ++s) {
    const SealingSegment& seg = segments[s];
    const std::string key = indexed("segments", s);
    if (seg.volume_a < kAmbient || seg.volume_a >= volumes) reject(key + ".volume_a", seg.volume_a, volume_rule.c_str());
    if (seg.volume_b < kAmbient || seg.volume_b >= volumes) reject(key + ".volume_b", seg.volume_b, volume_rule.c_str());
    if (seg.volume_a == seg.volume_b) reject(key + ".volume_b", seg.volume_b, "different from volume_a");
  }
  if (engines.size() > static_cast<std::size_t>(kMaxEngines)) {
    reject("engines.size", static_cast<double>(engines.size()), ("at most " + std::to_string(kMaxEngines)).c_str());
  }
  for (std::size_t e = 0; e < engines.size(); ++e) {
    const std::string key = indexed("engines", e);
    requirePositive(key + ".pressure_rise_max_pa", engines[e].pressure_rise_max_pa);
    requirePositive(key + ".volume_flow_max_m3ps", engines[e].volume_flow_max_m3ps);
    requirePositive(key + ".speed_lag_s", engines[e].speed_lag_s);
    const int chamber = engines[e].chamber;
    if (chamber == SuctionEngineParams::kPumpsReservoir ? !has_reservoir : (chamber < 0 || chamber >= n)) {
      reject(key + ".chamber", chamber,
             ("a chamber, 0.." + std::to_string(n - 1) + (has_reservoir ? ", or the reservoir, -1" : "")).c_str());
    }
  }
  if (has_reservoir) {
    requirePositive("valve.max_area_m2", valve.max_area_m2);
    requirePositive("valve.discharge_coefficient", valve.discharge_coefficient);
    if (valve.discharge_coefficient > 1.0) reject("valve.discharge_coefficient", valve.discharge_coefficient, "<= 1");
    requirePositive("valve.full_stroke_s", valve.full_stroke_s);
    if (!std::isfinite(valve.command_delay_s) || valve.command_delay_s < 0.0 || valve.command_delay_s > 1e3) {
      reject("valve.command_delay_s", valve.command_delay_s, "finite and in [0, 1000]");
    }
  }
  requirePositive("laminar_threshold_pa", laminar_threshold_pa);
  requirePositive("initial_step_s", initial_step_s);
  validateStepControl(step_control);
  if (step_control.error_components > volumes + 2) {
    reject("integrator.error_components", step_control.error_components,
           ("at most the ODE's " + std::to_string(volumes + 2) + " entries (0: every pressure)").c_str());
  }
  for (std::size_t f = 0; f < faults.size(); ++f) {
    const PlantFault& fault = faults[f];
    const std::string key = indexed("faults", f);
    if (fault.kind == PlantFault::Kind::kValveStuck) {
      if (valveCount() == 0) reject(key + ".chamber", fault.chamber, "a valve's chamber; the robot has no valves");
      if (fault.chamber < 1 || fault.chamber > n) {
        reject(key + ".chamber", fault.chamber, ("in 1.." + std::to_string(n)).c_str());
      }
      if (!(fault.opening >= 0.0 && fault.opening <= 1.0)) reject(key + ".opening", fault.opening, "in [0, 1]");
    } else if (fault.engine < 1 || fault.engine > static_cast<int>(engines.size())) {
      reject(key + ".engine", fault.engine, ("in 1.." + std::to_string(engines.size())).c_str());
    }
  }
}

std::int64_t ThermoParams::valveDelayNs() const { return std::llround(valve.command_delay_s * 1e9); }

}  // namespace climbsim::thermo
