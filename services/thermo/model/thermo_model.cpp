#include "thermo_model.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "airflow_system.hpp"
#include "dormand_prince.hpp"
#include "downforce.hpp"
#include "rosenbrock.hpp"
#include "suction_engine.hpp"
#include "valve_actuator.hpp"

namespace climbsim::thermo {
namespace {

// Openings closer than this to their target count as there (round-off of the ramps).
constexpr double kOpeningSnap = 1e-12;

void integrate(const ThermoParams& params, const OdeSystem& system, double t_end_s, OdeVector& y,
               double& step_s, IntegratorStats& stats, RhsCarry& carry) {
  switch (params.integrator) {
    case IntegratorKind::kRodas3:
      integrateRosenbrock(system, RosenbrockMethod::kRodas3, t_end_s, y, step_s, params.step_control, stats);
      return;
    case IntegratorKind::kRos2:
      integrateRosenbrock(system, RosenbrockMethod::kRos2, t_end_s, y, step_s, params.step_control, stats, &carry);
      return;
    case IntegratorKind::kDormandPrince:
      integrateDormandPrince(system, t_end_s, y, step_s, params.step_control, stats);
      return;
  }
}

}  // namespace

const ThermoParams& ThermoModel::validated(const ThermoParams& params) {
  params.validate();
  return params;
}

ThermoModel::ThermoModel(ThermoParams params) : params_(std::move(params)), layout_(validated(params_)) {
  valve_delay_ns_ = params_.valveDelayNs();
}

ThermoState ThermoModel::initialState(std::int64_t t_ns) const {
  ThermoState s;
  s.t_ns = t_ns;
  s.pressure_pa.assign(static_cast<std::size_t>(params_.volumeCount()), params_.gas.ambient_pressure_pa);
  s.valve_opening.assign(static_cast<std::size_t>(params_.valveCount()), 0.0);
  s.valve_target.assign(static_cast<std::size_t>(params_.valveCount()), 0.0);
  s.engine_speed.assign(params_.engines.size(), 0.0);
  s.engine_speed_command.assign(params_.engines.size(), 0.0);
  s.next_step_s = params_.initial_step_s;
  s.fault_in_force.assign(params_.faults.size(), 0);
  return s;
}

bool ThermoModel::fitsParams(const ThermoState& state) const {
  return state.pressure_pa.size() == static_cast<std::size_t>(params_.volumeCount()) &&
         state.valve_opening.size() == static_cast<std::size_t>(params_.valveCount()) &&
         state.valve_target.size() == state.valve_opening.size() &&
         state.engine_speed.size() == params_.engines.size() &&
         state.engine_speed_command.size() == params_.engines.size() &&
         state.fault_in_force.size() == params_.faults.size();
}

std::string ThermoModel::describeSizes(const ThermoState& state) {
  return "a state with " + std::to_string(state.pressure_pa.size()) + " pressures, " +
         std::to_string(state.valve_opening.size()) + " valves, " + std::to_string(state.engine_speed.size()) +
         " engines, " + std::to_string(state.fault_in_force.size()) + " faults";
}

std::string ThermoModel::describeParamsSizes() const {
  return std::to_string(params_.volumeCount()) + " pressures, " + std::to_string(params_.valveCount()) +
         " valves, " + std::to_string(params_.engines.size()) + " engines, " +
         std::to_string(params_.faults.size()) + " faults";
}

OdeVector ThermoModel::odeState(const ThermoState& state) const {
  const int volumes = params_.volumeCount();
  OdeVector y(volumes + 2);
  for (int i = 0; i < volumes; ++i) y[i] = state.pressure_pa[i];
  y[volumes] = state.ambient_inflow_kg;
  y[volumes + 1] = state.engine_outflow_kg;
  return y;
}

ThermoOutputs ThermoModel::outputsOf(const ThermoState& state, const std::vector<double>& leak_area_m2) const {
  if (!fitsParams(state) || leak_area_m2.size() != params_.segments.size()) {
    throw std::logic_error("thermo: outputsOf: " + describeSizes(state) + " and " +
                           std::to_string(leak_area_m2.size()) + " leak areas for a robot with " +
                           describeParamsSizes() + " and " + std::to_string(params_.segments.size()) + " segments");
  }
  ActuatorRamp ramp;
  std::copy(state.valve_opening.begin(), state.valve_opening.end(), ramp.valve_opening0.begin());
  std::copy(state.valve_opening.begin(), state.valve_opening.end(), ramp.valve_target.begin());
  ramp.engine_speed0 = state.engine_speed.data();
  ramp.engine_speed_command = state.engine_speed.data();
  for (double a : leak_area_m2) {
    if (!(std::isfinite(a) && a >= 0.0)) throw InvalidInputError("leak area " + std::to_string(a) + " m^2");
  }
  const OdeVector y = odeState(state);
  const AirflowSystem system(params_, layout_, leak_area_m2, ramp);
  ConnectionFlows flows;
  system.connectionFlows(0.0, y, flows);

  ThermoOutputs out;
  fillOutputs(state, flows, out);
  return out;
}

void ThermoModel::fillOutputs(const ThermoState& state, ConnectionFlows& flows, ThermoOutputs& out) const {
  out.t_ns = state.t_ns;
  out.pressure_pa = state.pressure_pa;
  out.segment_mass_flow_kgps = std::move(flows.segment_kgps);
  out.valve_mass_flow_kgps = std::move(flows.valve_kgps);
  out.engine_mass_flow_kgps = std::move(flows.engine_kgps);
  out.valve_opening = state.valve_opening;
  out.engine_speed = state.engine_speed;
  const Downforce d = computeDownforce(params_, state.pressure_pa);
  out.downforce_n = d.force_n;
  out.suction_moment_nm = d.moment_nm;
  out.p_RobotPF_m = d.p_RobotPF_m;
  out.ambient_inflow_kg = state.ambient_inflow_kg;
  out.engine_outflow_kg = state.engine_outflow_kg;
  const double krt = params_.gas.kappa * params_.gas.gas_constant_jpkgk * params_.gas.temperature_k;
  double air_mass_kg = 0.0;
  const int chambers = params_.chamberCount();
  for (int i = 0; i < chambers; ++i) air_mass_kg += state.pressure_pa[i] * params_.chamber_volume_m3[i] / krt;
  if (params_.has_reservoir) {
    air_mass_kg += state.pressure_pa[params_.reservoir()] * params_.reservoir_volume_m3 / krt;
  }
  out.air_mass_kg = air_mass_kg;
}

void ThermoModel::applyValveFaults(ThermoState& s, std::vector<double>& valve_command,
                                   std::int64_t t_ns, std::vector<std::size_t>& taking_effect) const {
  for (std::size_t f = 0; f < params_.faults.size(); ++f) {
    const PlantFault& fault = params_.faults[f];
    if (fault.kind != PlantFault::Kind::kValveStuck || fault.t_ns > t_ns) continue;
    const auto c = static_cast<std::size_t>(fault.chamber - 1);
    // Held equal to the target, the command queues nothing (queueValveCommands).
    valve_command[c] = fault.opening;
    if (s.fault_in_force[f] != 0) continue;
    // The valve sticks now, not one command delay later, and no command already on its way
    // reaches it.
    s.valve_target[c] = fault.opening;
    auto& pending = s.pending_valve_commands;
    pending.erase(std::remove_if(pending.begin(), pending.end(),
                                 [&](const PendingValveCommand& p) { return p.chamber == fault.chamber - 1; }),
                  pending.end());
    s.fault_in_force[f] = 1;
    taking_effect.push_back(f);
  }
}

void ThermoModel::applyEngineFaults(ThermoState& s, std::int64_t t_ns, std::vector<std::size_t>& taking_effect) const {
  for (std::size_t f = 0; f < params_.faults.size(); ++f) {
    const PlantFault& fault = params_.faults[f];
    if (fault.kind != PlantFault::Kind::kEngineFailure || fault.t_ns > t_ns) continue;
    s.engine_speed_command[static_cast<std::size_t>(fault.engine - 1)] = 0.0;
    if (s.fault_in_force[f] != 0) continue;
    s.fault_in_force[f] = 1;
    taking_effect.push_back(f);
  }
}

ThermoOutputs ThermoModel::step(ThermoState& state, const ThermoInputs& inputs, std::int64_t t_ns,
                                std::int64_t dt_ns) const {
  if (const std::string why = validateInputs(params_, inputs); !why.empty()) throw InvalidInputError(why);
  if (dt_ns <= 0 || t_ns != state.t_ns || !fitsParams(state)) {
    std::ostringstream os;
    os << "thermo: step(t_ns = " << t_ns << ", dt_ns = " << dt_ns << ") does not continue the state at t_ns = "
       << state.t_ns << " with " << describeSizes(state) << " (the robot: " << describeParamsSizes() << ")";
    throw std::logic_error(os.str());
  }

  // Work on a copy so that a failure leaves the caller's state as it was.
  // The copy goes into a per-thread scratch state whose vectors keep their capacity from
  // one call to the next (it is swapped with the caller's state at the end), so that a
  // period allocates nothing for it. Only a buffer: no value carries over.
  thread_local ThermoState scratch;
  ThermoState& s = scratch;
  s = state;
  // Room for this period's commands at once instead of growing the copy step by step.
  const int valves = params_.valveCount();
  s.pending_valve_commands.reserve(s.pending_valve_commands.size() + static_cast<std::size_t>(valves));
  ThermoOutputs out;
  thread_local std::vector<double> valve_command;  // a buffer, as `scratch`
  valve_command = inputs.valve_command;
  applyValveFaults(s, valve_command, t_ns, out.faults_taking_effect);
  queueValveCommands(s, valve_command, t_ns + valve_delay_ns_);
  for (std::size_t e = 0; e < inputs.engines.size(); ++e) {
    s.engine_speed_command[e] = inputs.engines[e].on ? inputs.engines[e].speed : 0.0;
  }
  applyEngineFaults(s, t_ns, out.faults_taking_effect);
  std::sort(out.faults_taking_effect.begin(), out.faults_taking_effect.end());
  applyDueValveCommands(s, t_ns);

  OdeVector y = odeState(s);

  const std::int64_t end_ns = t_ns + dt_ns;
  const double dt_s = static_cast<double>(dt_ns) * 1e-9;
  const double stroke_s = params_.valve.full_stroke_s;
  ActuatorRamp ramp;
  // The engine speeds stay those of t_ns until the end of the period (engine_t0_s moves).
  ramp.engine_speed_command = s.engine_speed_command.data();
  ramp.engine_speed0 = s.engine_speed.data();
  double tau_s = 0.0;  // local time since t_ns
  // f is continuous across the pieces of one period (openings are continuous; only their
  // rates jump), so the integrator may hand f at a piece's end to the next piece.
  RhsCarry carry;
  carry.stiffness_bound = s.stiffness_hint_per_s;
  // One system for every piece and the outputs: it reads the ramp by reference.
  const AirflowSystem system(params_, layout_, inputs.leak_area_m2, ramp);
  for (;;) {
    const std::int64_t next_activation_ns = nextValveActivationNs(s);
    const bool activation_ahead = next_activation_ns <= end_ns;
    const double tau_activation_s =
        activation_ahead ? static_cast<double>(next_activation_ns - t_ns) * 1e-9 : dt_s;
    // Pieces end where a valve's target jumps (activation) or a valve lands on its target:
    // inside a piece every opening is linear in time, so the integrator never steps
    // across a corner of the rate limit (a jump of d(opening)/dt that its error control
    // would otherwise find by trial and rejection).
    double piece_end_s = tau_activation_s;
    for (int c = 0; c < valves; ++c) {
      const double diff = s.valve_target[c] - s.valve_opening[c];
      ramp.valve_target[c] = s.valve_target[c];
      if (std::abs(diff) <= kOpeningSnap) {
        s.valve_opening[c] = s.valve_target[c];
        ramp.valve_rate_per_s[c] = 0.0;
        ramp.valve_reach_s[c] = 0.0;
      } else {
        ramp.valve_rate_per_s[c] = std::copysign(1.0 / stroke_s, diff);
        ramp.valve_reach_s[c] = std::abs(diff) * stroke_s;
        piece_end_s = std::min(piece_end_s, tau_s + ramp.valve_reach_s[c]);
      }
    }
    const double length_s = piece_end_s - tau_s;
    if (length_s > 0.0) {
      std::copy(s.valve_opening.begin(), s.valve_opening.end(), ramp.valve_opening0.begin());
      ramp.engine_t0_s = tau_s;
      system.rampChanged();
      integrate(params_, system, length_s, y, s.next_step_s, out.integrator, carry);
      for (int c = 0; c < valves; ++c) {
        // A valve that lands inside the interval lands exactly on its target.
        s.valve_opening[c] = ramp.valve_reach_s[c] <= length_s
                                 ? s.valve_target[c]
                                 : s.valve_opening[c] + ramp.valve_rate_per_s[c] * length_s;
      }
      tau_s = piece_end_s;
    } else {
      // A landing closer than the resolution of tau_s: land it here, or the loop would not move.
      for (int c = 0; c < valves; ++c) {
        if (ramp.valve_rate_per_s[c] != 0.0 && tau_s + ramp.valve_reach_s[c] <= tau_s) {
          s.valve_opening[c] = s.valve_target[c];
        }
      }
    }
    if (piece_end_s < tau_activation_s) continue;
    if (activation_ahead) applyDueValveCommands(s, next_activation_ns);
    if (!activation_ahead || next_activation_ns == end_ns) break;
  }

  // The engine commands hold over the whole period: one lag solution from its start.
  for (std::size_t e = 0; e < s.engine_speed.size(); ++e) {
    s.engine_speed[e] =
        engineSpeedAfter(s.engine_speed[e], s.engine_speed_command[e], params_.engines[e].speed_lag_s, dt_s);
  }
  const int volumes = params_.volumeCount();
  for (int i = 0; i < volumes; ++i) s.pressure_pa[i] = y[i];
  s.ambient_inflow_kg = y[volumes];
  s.engine_outflow_kg = y[volumes + 1];
  s.t_ns = end_ns;
  s.stiffness_hint_per_s = carry.stiffness_bound;

  std::copy(s.valve_opening.begin(), s.valve_opening.end(), ramp.valve_opening0.begin());
  std::copy(s.valve_opening.begin(), s.valve_opening.end(), ramp.valve_target.begin());
  ramp.valve_rate_per_s.fill(0.0);
  ramp.valve_reach_s.fill(0.0);
  ramp.engine_speed0 = s.engine_speed.data();
  ramp.engine_t0_s = 0.0;
  ConnectionFlows flows;
  system.rampChanged();
  system.connectionFlows(0.0, y, flows);

  fillOutputs(s, flows, out);  // s.t_ns = end_ns

  std::swap(state, s);
  return out;
}

}  // namespace climbsim::thermo
