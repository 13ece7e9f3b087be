#include "adhesion_controller.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "climbsim/errors.hpp"
#include "param_helpers.hpp"

namespace climbsim::controller {
namespace {

void requirePositive(const char* field, double value) { controller::requirePositive("adhesion controller", field, value); }

void requireIn(const char* field, double value, double lo, double hi, const char* range) {
  controller::requireIn("adhesion controller", field, value, lo, hi, range);
}

}  // namespace

AdhesionControllerParams adhesionControllerParamsFromRobot(const RobotDescription& robot,
                                                           const RobotGeometry& geometry) {
  if (!geometry.has_reservoir) {
    throw ConfigError("robot " + robot.name + ": no reservoir, so no valves: the adhesion controller commands one valve "
                      "per chamber on a reservoir");
  }
  AdhesionControllerParams p;
  p.ambient_pressure_pa = robot.gas.ambient_pressure_pa;
  addChambers(geometry, p);
  p.desired_downforce_n = robot.adhesion.desired_downforce_n;
  p.max_suction_pa = robot.engines.dp_max_pa;
  p.valve_full_stroke_s = robot.valves.full_stroke_s;
  p.valve_command_delay_s = robot.valves.command_delay_s;
  p.fan_max_suction_pa = robot.engines.dp_max_pa;
  return p;
}

AdhesionController::AdhesionController(AdhesionControllerParams params) : params_(params) {
  requirePositive("ambient_pressure_pa", params_.ambient_pressure_pa);
  if (params_.chamber_area_m2.empty() || params_.chamber_area_m2.size() > static_cast<std::size_t>(kMaxChambers) ||
      params_.p_RobotChamber_m.size() != params_.chamber_area_m2.size()) {
    throw ConfigError("adhesion controller: " + std::to_string(params_.chamber_area_m2.size()) + " chamber areas and " +
                      std::to_string(params_.p_RobotChamber_m.size()) + " centroids (must be 1.." +
                      std::to_string(kMaxChambers) + ", one each per chamber)");
  }
  for (int i = 0; i < chamberCount(); ++i) {
    requirePositive(("chamber_area_m2[" + std::to_string(i) + "]").c_str(), params_.chamber_area_m2[i]);
    for (double c : params_.p_RobotChamber_m[i]) {
      if (!std::isfinite(c)) throw ConfigError("adhesion controller: chamber centroid " + std::to_string(i + 1) + " is not finite");
    }
  }
  requirePositive("desired_downforce_n", params_.desired_downforce_n);
  requirePositive("max_suction_pa", params_.max_suction_pa);
  requirePositive("force_tau_s", params_.force_tau_s);
  requirePositive("balance_tau_s", params_.balance_tau_s);
  requirePositive("valve_gain_per_pa_s", params_.valve_gain_per_pa_s);
  requirePositive("valve_full_stroke_s", params_.valve_full_stroke_s);
  requireIn("valve_command_delay_s", params_.valve_command_delay_s, 0.0, 1e3, "[0, 1000]");
  requirePositive("isolate_leak_ratio", params_.isolate_leak_ratio);
  requirePositive("retry_initial_s", params_.retry_initial_s);
  requireIn("force_demand_max_ratio", params_.force_demand_max_ratio, 1.0, 1e3, "[1, 1000]");
  requireIn("reservoir_tracking_ratio", params_.reservoir_tracking_ratio, 1e-12, 1.0 - 1e-12, "(0, 1)");
  requireIn("max_trim", params_.max_trim, 0.0, 1.0 - 1e-12, "[0, 1)");
  requireIn("isolate_min_opening", params_.isolate_min_opening, 1e-12, 1.0, "(0, 1]");
  requireIn("isolate_min_reservoir_suction_pa", params_.isolate_min_reservoir_suction_pa, 0.0, 1e9, ">= 0");
  requireIn("isolate_delay_s", params_.isolate_delay_s, 0.0, 1e9, ">= 0");
  requireIn("min_isolation_s", params_.min_isolation_s, 0.0, 1e9, ">= 0");
  requireIn("reseal_suction_ratio", params_.reseal_suction_ratio, 1e-12, 1.0 - 1e-12, "(0, 1)");
  requireIn("retry_max_s", params_.retry_max_s, params_.retry_initial_s, 1e9, ">= retry_initial_s");
  requireIn("probe_rise_ratio", params_.probe_rise_ratio, 1e-12, 1.0 - 1e-12, "(0, 1)");
  requireIn("isolate_shortfall_ratio", params_.isolate_shortfall_ratio, 0.0, 1.0 - 1e-12, "[0, 1)");
  requireIn("isolate_saturated_s", params_.isolate_saturated_s, 0.0, 1e9, ">= 0");
  requireIn("probe_check_s", params_.probe_check_s, 0.0, 1e9, ">= 0");
  requirePositive("probe_ramp_s", params_.probe_ramp_s);
  requireIn("readmit_max_opening", params_.readmit_max_opening, 1e-12, 1.0 - 1e-12, "(0, 1)");
  requireIn("readmit_tolerance_ratio", params_.readmit_tolerance_ratio, 0.0, 1.0 - 1e-12, "[0, 1)");
  requireIn("readmit_hold_s", params_.readmit_hold_s, 0.0, 1e9, ">= 0");
  requireIn("probe_opening", params_.probe_opening, 1e-12, 1.0, "(0, 1]");
  requireIn("probe_s", params_.probe_s, 0.0, 1e9, ">= 0");
  requireIn("valve_prop_per_pa", params_.valve_prop_per_pa, 0.0, 1.0, "[0, 1]");
  requireIn("overshoot_guard_ratio", params_.overshoot_guard_ratio, 1.0, 1e3, "[1, 1000]");
  requireIn("fan_max_suction_pa", params_.fan_max_suction_pa, 1e-12, params_.ambient_pressure_pa * (1.0 - 1e-12),
            "(0, ambient_pressure_pa)");
  requireIn("flood_gain_ratio", params_.flood_gain_ratio, 0.0, 1e3, "[0, 1000]");
  requirePositive("flood_min_leak_ratio", params_.flood_min_leak_ratio);
  requireIn("flood_isolate_s", params_.flood_isolate_s, 0.0, 1e9, ">= 0");
  requirePositive("flood_retry_initial_s", params_.flood_retry_initial_s);
  requireIn("flood_demand_max_ratio", params_.flood_demand_max_ratio, 1.0, 1e3, "[1, 1000]");
  for (double a : params_.chamber_area_m2) total_area_m2_ += a;
}

AdhesionControllerState AdhesionController::initialState() const {
  AdhesionControllerState state;
  state.desired_downforce_n = params_.desired_downforce_n;
  state.force_demand_n = params_.desired_downforce_n;
  // The uniform suction that gives F*: where the force loop starts.
  state.s_base_pa = std::min(state.force_demand_n / total_area_m2_, params_.max_suction_pa);
  const auto n = static_cast<std::size_t>(chamberCount());
  for (auto* v : {&state.trim, &state.opening, &state.expected_opening, &state.verdict_s, &state.short_s, &state.state_s,
                  &state.probe_start_suction_pa, &state.ok_s, &state.last_error_pa}) {
    v->assign(n, 0.0);
  }
  for (auto* v : {&state.isolated, &state.flood_isolated, &state.probing, &state.probe_ramp, &state.flood_candidates}) {
    v->assign(n, false);
  }
  state.retry_s.assign(n, params_.retry_initial_s);
  return state;
}

void AdhesionController::setDesiredDownforce(AdhesionControllerState& state, double downforce_n) const {
  requirePositive("desired_downforce_n", downforce_n);
  // Keep what the integral learnt (the leaks), shift it by the change of set-point.
  state.force_demand_n = std::clamp(state.force_demand_n + (downforce_n - state.desired_downforce_n), 0.0,
                                    params_.force_demand_max_ratio * downforce_n);
  state.desired_downforce_n = downforce_n;
}

double AdhesionController::predictedReservoirSuction(double fan_scale, double leak_flow_scale) const {
  // Steady flow balance q_fan(s) = G sqrt(s): q_fan falls and G sqrt(s) rises with s, so the
  // root is bracketed in [0, s_max] and bisection finds it in a fixed number of steps.
  const AdhesionControllerParams& p = params_;
  double lo = 0.0;
  double hi = p.fan_max_suction_pa;
  for (int k = 0; k < 48; ++k) {
    const double mid = 0.5 * (lo + hi);
    const double fan = fan_scale * (p.ambient_pressure_pa - mid) * (1.0 - mid / p.fan_max_suction_pa);
    if (fan > leak_flow_scale * std::sqrt(mid)) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return lo;
}

void AdhesionController::floodIsolation(AdhesionControllerState& st, const AdhesionMeasurement& m, double dt_s,
                                        double reservoir_suction_pa,
                                        const std::vector<bool>& isolated_before) const {
  const AdhesionControllerParams& p = params_;
  st.flood_candidates.assign(st.flood_candidates.size(), false);
  st.flood_predicted_n = 0.0;
  st.flood_predicted_all_n = 0.0;
  // Judged only in a settled state: no chamber changed sides in this step, every isolated valve
  // closed or at the probe's small opening (a trial's flow would be blamed on the others), the
  // reservoir pulling and below the fan curve's end, F short of F*, and some admitted valve fully
  // open (the valves cannot pull harder: the reservoir is the limit).
  bool evaluable = st.isolated == isolated_before && reservoir_suction_pa >= p.isolate_min_reservoir_suction_pa &&
                   reservoir_suction_pa < p.fan_max_suction_pa &&
                   m.downforce_n < (1.0 - p.isolate_shortfall_ratio) * st.desired_downforce_n;
  bool any_open = false;
  int admitted = 0;
  double flow = 0.0;            // sum_j û_j sqrt(s_R - s_j): the valves' flow / (A_v sqrt(2 rho))
  double isolated_force_n = 0.0;
  std::vector<double> leak2(st.opening.size(), 0.0);  // lambda_i²
  std::vector<double> keep(st.opening.size(), 0.0);   // k_i = s_i / s_R at the most the chamber can hold
  for (int i = 0; i < chamberCount(); ++i) {
    const double suction_pa = p.ambient_pressure_pa - m.pressure_pa[i];
    const double u = st.expected_opening[i];
    flow += u * std::sqrt(std::max(0.0, reservoir_suction_pa - suction_pa));
    if (st.isolated[i]) {
      isolated_force_n += p.chamber_area_m2[i] * std::max(0.0, suction_pa);
      if (u > p.probe_opening || st.opening[i] > p.probe_opening) evaluable = false;
      continue;
    }
    ++admitted;
    if (u >= 1.0) any_open = true;
    if (suction_pa <= 0.0) {
      evaluable = false;  // open to the ambient: step 2's crack verdict is the one to act
      continue;
    }
    leak2[i] = u * u * std::max(0.0, reservoir_suction_pa - suction_pa) / suction_pa;
    keep[i] = std::min(p.reservoir_tracking_ratio, 1.0 / (1.0 + leak2[i]));
  }
  if (!(evaluable && any_open && admitted > 1 && flow > 0.0)) {
    st.flood_s = 0.0;
    return;
  }
  // The fan curve through the present operating point: q_fan(s) = c (p_o - s) (1 - s / s_max).
  const double fan_scale =
      flow / ((p.ambient_pressure_pa - reservoir_suction_pa) * (1.0 - reservoir_suction_pa / p.fan_max_suction_pa));
  // F predicted with the chambers in `out` isolated (those pulling nothing), capped at F*.
  const auto predicted = [&](const std::vector<bool>& out) {
    double leak_flow_scale = 0.0;
    double held_area_m2 = 0.0;
    for (int i = 0; i < chamberCount(); ++i) {
      if (st.isolated[i] || out[i]) continue;
      leak_flow_scale += std::sqrt(leak2[i] * keep[i]);
      held_area_m2 += p.chamber_area_m2[i] * keep[i];
    }
    const double s_r = predictedReservoirSuction(fan_scale, leak_flow_scale);
    return std::min(st.desired_downforce_n, isolated_force_n + s_r * held_area_m2);
  };
  std::vector<bool> out(st.opening.size(), false);
  const double all_n = predicted(out);
  double best_n = all_n;
  std::vector<bool> best(st.opening.size(), false);
  const double min_leak2 = p.flood_min_leak_ratio * p.flood_min_leak_ratio;
  // Candidates: the k leakiest admitted chambers, k = 1 .. admitted - 1 (one always stays).
  for (int k = 1; k < admitted; ++k) {
    int next = -1;
    for (int i = 0; i < chamberCount(); ++i) {
      if (st.isolated[i] || out[i] || leak2[i] < min_leak2) continue;
      if (next < 0 || leak2[i] > leak2[next]) next = i;
    }
    if (next < 0) break;
    out[next] = true;
    const double f_n = predicted(out);
    if (f_n > best_n) {
      best_n = f_n;
      best = out;
    }
  }
  st.flood_predicted_all_n = all_n;
  st.flood_predicted_n = best_n;
  st.flood_candidates = best;
  st.flood_s = best_n > (1.0 + p.flood_gain_ratio) * all_n ? st.flood_s + dt_s : 0.0;
  if (st.flood_s < p.flood_isolate_s || st.flood_s <= 0.0) return;
  st.flood_s = 0.0;
  for (int i = 0; i < chamberCount(); ++i) {
    if (!best[i]) continue;
    st.isolated[i] = true;
    st.flood_isolated[i] = true;
    // The first retry waits until the reservoir and the others have settled on the new set (a
    // probe's rise during that transient would be the neighbours', not a re-seal).
    st.retry_s[i] = std::min(p.flood_retry_initial_s, p.retry_max_s);
    st.state_s[i] = 0.0;
    st.verdict_s[i] = 0.0;
    st.short_s[i] = 0.0;
    // Its valve closes at the trial's rate (step 5), so that the others take its share over as
    // the reservoir recovers, without the dip of a valve shut at once.
    st.probe_ramp[i] = st.opening[i] > 0.0;
    ++st.isolation_count;
    ++st.flood_isolation_count;
  }
}

AdhesionControllerOutputs AdhesionController::step(AdhesionControllerState& state, const AdhesionControllerInputs& m,
                                                   std::int64_t /*t_ns*/, std::int64_t dt_ns) const {
  if (dt_ns <= 0) throw std::invalid_argument("adhesion controller: dt_ns must be > 0");
  const double dt_s = 1e-9 * static_cast<double>(dt_ns);
  bool finite = std::isfinite(m.downforce_n) && std::isfinite(m.p_RobotPF_m[0]) && std::isfinite(m.p_RobotPF_m[1]);
  for (double p : m.pressure_pa) finite = finite && std::isfinite(p);
  if (!finite) throw std::invalid_argument("adhesion controller: measurement is not finite");
  if (m.pressure_pa.size() != static_cast<std::size_t>(chamberCount()) + 1) {
    throw std::invalid_argument("adhesion controller: " + std::to_string(m.pressure_pa.size()) + " pressures for " +
                                std::to_string(chamberCount()) + " chambers and the reservoir");
  }

  const AdhesionControllerParams& p = params_;
  AdhesionControllerState& st = state;
  const double reservoir_suction_pa = p.ambient_pressure_pa - m.pressure_pa[static_cast<std::size_t>(chamberCount())];
  const double force_error_n = st.desired_downforce_n - m.downforce_n;

  // 1. Where the valves should be by now.
  const double max_move = dt_s / p.valve_full_stroke_s;
  for (int i = 0; i < chamberCount(); ++i) {
    st.expected_opening[i] += std::clamp(st.opening[i] - st.expected_opening[i], -max_move, max_move);
  }

  // 2. Isolate a chamber whose leak its valve cannot make up; re-admit one that has re-sealed or
  //    whose probe shows that its valve can.
  const double ratio2 = p.isolate_leak_ratio * p.isolate_leak_ratio;
  const double cap_pa = p.reservoir_tracking_ratio * reservoir_suction_pa;
  const bool judged = reservoir_suction_pa >= p.isolate_min_reservoir_suction_pa;
  bool probing_any = false;
  for (int i = 0; i < chamberCount(); ++i) probing_any = probing_any || st.probing[i];
  const std::vector<bool> isolated_before = st.isolated;
  for (int i = 0; i < chamberCount(); ++i) {
    const double suction_pa = p.ambient_pressure_pa - m.pressure_pa[i];
    const double u = st.expected_opening[i];
    // Far beyond any valve: lambda_i = u sqrt((s_R - s_i) / s_i) over isolate_leak_ratio.
    const bool flooding = judged && u >= p.isolate_min_opening &&
                          u * u * (reservoir_suction_pa - suction_pa) > ratio2 * suction_pa;
    // The chamber's share of the force: the common target, or its trimmed one when that is lower,
    // and never more than the reservoir allows.
    const double share_pa = st.s_base_pa * std::min(1.0, 1.0 - st.trim[i]);
    st.state_s[i] += dt_s;
    if (!st.isolated[i]) {
      // Cannot compensate: valve fully open, the reservoir not the limit, and still short.
      const bool short_open = judged && u >= 1.0 && share_pa < cap_pa &&
                              suction_pa < (1.0 - p.isolate_shortfall_ratio) * share_pa;
      st.verdict_s[i] = flooding ? st.verdict_s[i] + dt_s : 0.0;
      st.short_s[i] = short_open ? st.short_s[i] + dt_s : 0.0;
      if ((flooding && st.verdict_s[i] >= p.isolate_delay_s) ||
          (short_open && st.short_s[i] >= p.isolate_saturated_s)) {
        st.isolated[i] = true;
        st.retry_s[i] = p.retry_initial_s;
        st.state_s[i] = 0.0;
        st.verdict_s[i] = 0.0;
        st.short_s[i] = 0.0;
        st.opening[i] = 0.0;
        ++st.isolation_count;
      }
    } else if (st.probing[i] && !st.probe_ramp[i]) {
      // Leak check at the small probe opening. Holds (re-seal suction), or answers the probe's
      // small flow with a rise that only a nearly sealed chamber can give: re-admitted at once,
      // the valve loop goes on from the probe's opening (bumpless).
      const bool holds = suction_pa >= p.reseal_suction_ratio * st.s_base_pa;
      const bool rises = judged && suction_pa - st.probe_start_suction_pa[i] >= p.probe_rise_ratio * reservoir_suction_pa;
      if (holds || rises) {
        st.probing[i] = false;
        probing_any = false;
        st.isolated[i] = false;
        st.state_s[i] = 0.0;
      } else if (st.state_s[i] >= p.probe_check_s) {
        // Else a trial if the leak is not far beyond the valve. The leak carries what the valve
        // and the neighbours take out, A_leak sqrt(2 rho s_i) = u A_v sqrt(2 rho (s_R - s_i)) + q_n,
        // and before the probe A_leak sqrt(2 rho s_i,0) = q_n; with the neighbours' q_n about
        // the same, lambda = u sqrt(s_R - s_i) / (sqrt(s_i) - sqrt(s_i,0)).
        const double rise_pa = std::sqrt(std::max(0.0, suction_pa)) - std::sqrt(std::max(0.0, st.probe_start_suction_pa[i]));
        if (judged && rise_pa > 0.0 && u * u * (reservoir_suction_pa - suction_pa) <= ratio2 * rise_pa * rise_pa) {
          st.probe_ramp[i] = true;  // step 5 opens the valve from the probe's opening
          st.ok_s[i] = 0.0;
        } else {
          st.probing[i] = false;
          probing_any = false;
          st.state_s[i] = 0.0;
          st.retry_s[i] = std::min(2.0 * st.retry_s[i], p.retry_max_s);
          st.opening[i] = 0.0;
        }
      }
    } else if (st.probing[i]) {
      // Trial: the valve opens at a constant rate (step 5) until the chamber holds its share. It
      // can compensate when it holds it with the valve not beyond readmit_max_opening; it cannot
      // when the valve is fully open and it is still short, or when its leak estimate floods.
      const double target_pa = std::min(share_pa, cap_pa);
      const bool on_target = suction_pa >= (1.0 - p.readmit_tolerance_ratio) * target_pa;
      st.ok_s[i] = on_target && u <= p.readmit_max_opening ? st.ok_s[i] + dt_s : 0.0;
      if (st.ok_s[i] >= p.readmit_hold_s) {
        st.probing[i] = false;  // re-admitted; bumpless: the valve loop goes on from the trial's opening
        st.probe_ramp[i] = false;
        probing_any = false;
        st.isolated[i] = false;
        st.state_s[i] = 0.0;
      } else if (flooding || (u >= 1.0 && !on_target) || st.state_s[i] >= p.probe_s) {
        // Its valve cannot make the leak up: stays isolated, retries later. The valve closes at
        // the trial's rate (step 5), so that the others take its share over without a dip, or
        // at once when the leak floods.
        st.probing[i] = false;
        st.probe_ramp[i] = !flooding;
        probing_any = false;
        st.state_s[i] = 0.0;
        st.retry_s[i] = std::min(2.0 * st.retry_s[i], p.retry_max_s);
        if (flooding) st.opening[i] = 0.0;
      }
    } else if (st.probe_ramp[i]) {
      // Closing after a failed trial: its suction says nothing about a re-seal yet.
    } else if (st.state_s[i] >= p.min_isolation_s) {
      if (suction_pa >= p.reseal_suction_ratio * st.s_base_pa) {
        st.isolated[i] = false;  // re-sealed; bumpless: the valve loop starts from the closed valve
        st.state_s[i] = 0.0;
      } else if (st.state_s[i] >= st.retry_s[i] && !probing_any) {
        st.probing[i] = true;
        st.probe_ramp[i] = false;
        probing_any = true;
        st.state_s[i] = 0.0;
        st.opening[i] = p.probe_opening;
        st.probe_start_suction_pa[i] = suction_pa;
        ++st.probe_count;
      }
    }
  }

  // 2b. Several leaks flooding the reservoir together: give up the set of leakiest chambers
  //     whose isolation the reservoir's flow balance predicts to pay.
  floodIsolation(st, m, dt_s, reservoir_suction_pa, isolated_before);

  // 3. Force loop on the admitted area, less what the isolated chambers pull by themselves.
  double admitted_area_m2 = 0.0;
  double isolated_force_n = 0.0;
  for (int i = 0; i < chamberCount(); ++i) {
    if (!st.isolated[i]) {
      admitted_area_m2 += p.chamber_area_m2[i];
    } else {
      isolated_force_n += p.chamber_area_m2[i] * std::max(0.0, p.ambient_pressure_pa - m.pressure_pa[i]);
    }
  }
  const auto suction_for = [&](double demand_n) {
    return admitted_area_m2 > 0.0
               ? std::min(std::max(0.0, demand_n - isolated_force_n) / admitted_area_m2, p.max_suction_pa)
               : p.max_suction_pa;
  };
  bool can_pull_harder = false;
  {
    const double s_now = suction_for(st.force_demand_n);
    for (int i = 0; i < chamberCount(); ++i) {
      if (!st.isolated[i] && st.opening[i] < 1.0 && s_now * (1.0 - st.trim[i]) < cap_pa) can_pull_harder = true;
    }
  }
  // Conditional integration: asking for more while no admitted chamber can give more (engines
  // spinning up, the reservoir flooded, every valve open) would only wind the demand up.
  if (force_error_n < 0.0 || can_pull_harder) st.force_demand_n += dt_s * force_error_n / p.force_tau_s;
  // Back-calculation: beyond F* the demand never exceeds what the admitted chambers give at the
  // reservoir cap, so nothing is stored up that would come out as an overshoot later.
  // While chambers are given up for a flooded reservoir (step 2b), the demand stays within
  // flood_demand_max_ratio F*: what it asks beyond F* is stored as suction in the others, and it
  // comes out as an overshoot when the given-up chambers re-seal through their walls.
  bool flood_isolated_any = false;
  for (int i = 0; i < chamberCount(); ++i) {
    st.flood_isolated[i] = st.flood_isolated[i] && st.isolated[i];
    flood_isolated_any = flood_isolated_any || st.flood_isolated[i];
  }
  const double demand_max_ratio =
      flood_isolated_any ? std::min(p.force_demand_max_ratio, p.flood_demand_max_ratio) : p.force_demand_max_ratio;
  const double achievable_n = std::max(st.desired_downforce_n, admitted_area_m2 * cap_pa);
  st.force_demand_n = std::clamp(st.force_demand_n, 0.0,
                               std::min(demand_max_ratio * st.desired_downforce_n, achievable_n));
  st.s_base_pa = suction_for(st.force_demand_n);

  // 4. and 5. Balance trims and valve loops of the admitted chambers.
  const bool overshooting = m.downforce_n > p.overshoot_guard_ratio * st.desired_downforce_n;
  // F where it will be when a command given now acts (a sample and the command delay ahead).
  const double force_ahead_n =
      m.downforce_n + (m.downforce_n - st.last_downforce_n) * (p.valve_command_delay_s + dt_s) / dt_s;
  for (int i = 0; i < chamberCount(); ++i) {
    if (st.isolated[i]) {
      if (!st.probing[i] && st.probe_ramp[i]) {
        st.opening[i] = std::max(0.0, st.opening[i] - dt_s / p.probe_ramp_s);  // closing after a failed trial
        st.probe_ramp[i] = st.opening[i] > 0.0;
      } else if (!st.probing[i]) {
        st.opening[i] = 0.0;
      } else if (!st.probe_ramp[i]) {
        st.opening[i] = p.probe_opening;
      } else if (st.ok_s[i] <= 0.0) {
        st.opening[i] = std::min(1.0, st.opening[i] + dt_s / p.probe_ramp_s);  // trial: open until it holds
      }
      // The error it would have, so that re-admission brings no proportional kick (bumpless).
      st.last_error_pa[i] = std::min(st.s_base_pa * (1.0 - st.trim[i]), cap_pa) - (p.ambient_pressure_pa - m.pressure_pa[i]);
      continue;
    }
    const auto& c = p.p_RobotChamber_m[i];
    const double r_m = std::hypot(c[0], c[1]);
    // The centre chamber's centroid is the origin: it has no side to trim.
    if (p.balance && r_m > 1e-9) {
      const double towards = (m.p_RobotPF_m[0] * c[0] + m.p_RobotPF_m[1] * c[1]) / (r_m * r_m);
      // A fully open valve cannot pull harder: raising its target further only winds the trim up.
      const bool saturated = st.opening[i] >= 1.0 && towards < 0.0;
      if (!saturated) {
        st.trim[i] = std::clamp(st.trim[i] + dt_s * towards / p.balance_tau_s, -p.max_trim, p.max_trim);
      }
    } else {
      st.trim[i] = 0.0;
    }
    const double target_pa = std::min(st.s_base_pa * (1.0 - st.trim[i]), cap_pa);
    const double suction_pa = p.ambient_pressure_pa - m.pressure_pa[i];
    // Reservoir feed-forward: when the reservoir pulls harder (a leak has just stopped), the
    // same valve flow u sqrt(s_R - s_i) needs a smaller opening; cut it at once instead of
    // waiting for the chamber to overshoot. Above the cap (the chamber follows a flooded
    // reservoir) the factor is ill-conditioned and only while F is heading over F* is it wanted.
    if (reservoir_suction_pa > suction_pa && st.last_reservoir_suction_pa > suction_pa &&
        (suction_pa <= cap_pa || force_ahead_n >= st.desired_downforce_n)) {
      st.opening[i] = std::min(
          1.0, st.opening[i] * std::sqrt((st.last_reservoir_suction_pa - suction_pa) / (reservoir_suction_pa - suction_pa)));
    }
    // Velocity-form PI: the clamp is the integrator's own limit, so it cannot wind up.
    const double error_pa = target_pa - suction_pa;
    st.opening[i] = std::clamp(st.opening[i] + dt_s * p.valve_gain_per_pa_s * error_pa +
                                 p.valve_prop_per_pa * (error_pa - st.last_error_pa[i]),
                             0.0, 1.0);
    st.last_error_pa[i] = error_pa;
    // Overshoot guard: deeper than its target (the reservoir has just recovered from a leak,
    // say), a chamber gets at most the opening that the orifice law says would hold the target
    // with its present leak: u* = û sqrt((s_R - s_i) s* / (s_i (s_R - s*))). Integral action alone
    // would close the valve far slower than the reservoir recovers.
    if (overshooting && suction_pa > target_pa) {
      double guard = 0.0;
      if (target_pa > 0.0 && reservoir_suction_pa > suction_pa && reservoir_suction_pa > target_pa) {
        guard = st.expected_opening[i] * std::sqrt(((reservoir_suction_pa - suction_pa) * target_pa) /
                                                 (suction_pa * (reservoir_suction_pa - target_pa)));
      }
      st.opening[i] = std::min(st.opening[i], guard);
    }
  }
  st.last_reservoir_suction_pa = reservoir_suction_pa;
  st.last_downforce_n = m.downforce_n;
  return AdhesionControllerOutputs{st.opening};
}

}  // namespace climbsim::controller
