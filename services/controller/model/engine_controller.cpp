#include "engine_controller.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "climbsim/errors.hpp"
#include "param_helpers.hpp"

namespace climbsim::controller {
namespace {

constexpr const char* kWho = "engine controller";

}  // namespace

EngineControllerParams engineControllerParamsFromRobot(const RobotDescription& robot, const RobotGeometry& geometry) {
  if (geometry.has_reservoir) {
    throw ConfigError("robot " + robot.name + ": a reservoir with valves: its downforce is held by the valves, not by "
                      "the engines' speed");
  }
  EngineControllerParams p;
  p.ambient_pressure_pa = robot.gas.ambient_pressure_pa;
  addChambers(geometry, p);
  for (int c : robot.engines.chambers) p.engine_chamber.push_back(c - 1);
  p.desired_downforce_n = robot.adhesion.desired_downforce_n;
  p.max_suction_pa = robot.engines.dp_max_pa;
  p.engine_integral_s = std::max(robot.engines.speed_lag_s, kMinEngineIntegralS);
  return p;
}

EngineController::EngineController(EngineControllerParams params) : params_(std::move(params)) {
  const auto n = params_.chamber_area_m2.size();
  if (n == 0 || n > static_cast<std::size_t>(kMaxChambers) || params_.p_RobotChamber_m.size() != n) {
    throw ConfigError(std::string(kWho) + ": " + std::to_string(n) + " chamber areas and " +
                      std::to_string(params_.p_RobotChamber_m.size()) + " centroids (must be 1.." +
                      std::to_string(kMaxChambers) + ", one each per chamber)");
  }
  if (params_.engine_chamber.empty() || params_.engine_chamber.size() > static_cast<std::size_t>(kMaxEngines)) {
    throw ConfigError(std::string(kWho) + ": " + std::to_string(params_.engine_chamber.size()) +
                      " engines (must be 1.." + std::to_string(kMaxEngines) + ")");
  }
  pumped_.assign(n, false);
  for (std::size_t k = 0; k < params_.engine_chamber.size(); ++k) {
    const int c = params_.engine_chamber[k];
    if (c < 0 || c >= static_cast<int>(n)) {
      throw ConfigError(std::string(kWho) + ": engine " + std::to_string(k + 1) + " pumps chamber " +
                        std::to_string(c + 1) + " (the robot has chambers 1.." + std::to_string(n) + ")");
    }
    pumped_[static_cast<std::size_t>(c)] = true;
  }
  for (std::size_t i = 0; i < n; ++i) {
    requirePositive(kWho, ("chamber_area_m2[" + std::to_string(i) + "]").c_str(), params_.chamber_area_m2[i]);
    for (double c : params_.p_RobotChamber_m[i]) {
      if (!std::isfinite(c)) throw ConfigError(std::string(kWho) + ": chamber centroid " + std::to_string(i + 1) + " is not finite");
    }
  }
  requirePositive(kWho, "ambient_pressure_pa", params_.ambient_pressure_pa);
  requirePositive(kWho, "desired_downforce_n", params_.desired_downforce_n);
  requirePositive(kWho, "max_suction_pa", params_.max_suction_pa);
  requirePositive(kWho, "engine_integral_s", params_.engine_integral_s);
  requireIn(kWho, "engine_prop", params_.engine_prop, 0.0, 1e3, "[0, 1000]");
  requirePositive(kWho, "balance_tau_s", params_.balance_tau_s);
  requireIn(kWho, "max_trim", params_.max_trim, 0.0, 0.99, "[0, 0.99]");
}

EngineControllerState EngineController::initialState() const {
  EngineControllerState state;
  state.desired_downforce_n = params_.desired_downforce_n;
  state.trim.assign(params_.chamber_area_m2.size(), 0.0);
  state.target_pa.assign(params_.chamber_area_m2.size(), 0.0);
  for (auto* v : {&state.speed, &state.last_error, &state.last_feedforward}) v->assign(params_.engine_chamber.size(), 0.0);
  return state;
}

EngineControllerOutputs EngineController::step(EngineControllerState& state, const AdhesionMeasurement& m,
                                               std::int64_t /*t_ns*/, std::int64_t dt_ns) const {
  if (dt_ns <= 0) throw std::invalid_argument("engine controller: dt_ns must be > 0");
  const int n = chamberCount();
  if (m.pressure_pa.size() != static_cast<std::size_t>(n)) {
    throw std::invalid_argument("engine controller: " + std::to_string(m.pressure_pa.size()) + " pressures for " +
                                std::to_string(n) + " chambers (no reservoir)");
  }
  bool finite = std::isfinite(m.downforce_n) && std::isfinite(m.p_RobotPF_m[0]) && std::isfinite(m.p_RobotPF_m[1]);
  for (double p : m.pressure_pa) finite = finite && std::isfinite(p);
  if (!finite) throw std::invalid_argument("engine controller: measurement is not finite");
  const EngineControllerParams& p = params_;
  EngineControllerState& st = state;
  const double dt_s = 1e-9 * static_cast<double>(dt_ns);

  // 1. What the chambers without an engine pull by themselves.
  double unpumped_force_n = 0.0;
  for (int i = 0; i < n; ++i) {
    if (!pumped_[i]) unpumped_force_n += p.chamber_area_m2[i] * std::max(0.0, p.ambient_pressure_pa - m.pressure_pa[i]);
  }

  // 2. Balance trims of the pumped chambers off the centre.
  for (int i = 0; i < n; ++i) {
    const auto& c = p.p_RobotChamber_m[i];
    const double r2_m2 = c[0] * c[0] + c[1] * c[1];
    if (!p.balance || !pumped_[i] || r2_m2 <= 1e-18) {
      st.trim[i] = 0.0;
      continue;
    }
    const double towards = (m.p_RobotPF_m[0] * c[0] + m.p_RobotPF_m[1] * c[1]) / r2_m2;
    // Every engine on it at full speed: a higher target only winds the trim up.
    bool saturated = towards < 0.0;
    for (std::size_t k = 0; k < p.engine_chamber.size(); ++k) {
      if (p.engine_chamber[k] == i) saturated = saturated && st.speed[k] >= 1.0;
    }
    if (!saturated) st.trim[i] = std::clamp(st.trim[i] + dt_s * towards / p.balance_tau_s, -p.max_trim, p.max_trim);
  }

  // 3. The pumped chambers' shares of F*.
  double weighted_area_m2 = 0.0;
  for (int i = 0; i < n; ++i) {
    if (pumped_[i]) weighted_area_m2 += p.chamber_area_m2[i] * (1.0 - st.trim[i]);
  }
  const double common_pa = std::max(0.0, st.desired_downforce_n - unpumped_force_n) / weighted_area_m2;
  for (int i = 0; i < n; ++i) {
    st.target_pa[i] = pumped_[i] ? std::min(common_pa * (1.0 - st.trim[i]), p.max_suction_pa) : 0.0;
  }

  // 4. Each engine's PI on its chamber's normalised error, with the fan curve's feed-forward.
  EngineControllerOutputs out;
  out.engine_speed.resize(p.engine_chamber.size());
  for (std::size_t k = 0; k < p.engine_chamber.size(); ++k) {
    const int c = p.engine_chamber[k];
    const double target_pa = st.target_pa[c];
    const double error = (target_pa - (p.ambient_pressure_pa - m.pressure_pa[c])) / p.max_suction_pa;
    const double feedforward = std::sqrt(target_pa / p.max_suction_pa);
    st.speed[k] = std::clamp(st.speed[k] + (feedforward - st.last_feedforward[k]) +
                                 p.engine_prop * (error - st.last_error[k]) + dt_s * error / p.engine_integral_s,
                             0.0, 1.0);
    st.last_error[k] = error;
    st.last_feedforward[k] = feedforward;
    out.engine_speed[k] = st.speed[k];
  }
  return out;
}

}  // namespace climbsim::controller
