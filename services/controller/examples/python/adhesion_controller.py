"""The reference adhesion controller in Python: a line-by-line port of
services/controller/model/adhesion_controller.cpp (same loops, same order of operations, so
the same numbers bit for bit; the header there has the equations). Pure Python: no DDS.

Per step: (1) expected valve positions u^_i (rate-limited command); (2) isolation: an admitted
chamber whose leak estimate lambda_i = u^_i sqrt((s_R - s_i) / s_i) is above isolate_leak_ratio for
isolate_delay_s, or whose valve is fully open while it stays short of its share by
isolate_shortfall_ratio for isolate_saturated_s (the reservoir not the limit), is isolated (valve
closed); an isolated one is re-admitted when it holds s_i >= reseal_suction_ratio * s_base with
its valve closed, or after a probe (one chamber at a time, intervals doubling while probes fail):
a leak check at probe_opening for probe_check_s re-admits on that suction or a rise of
probe_rise_ratio * s_R; else, if lambda = u sqrt(s_R - s_i) / (sqrt(s_i) - sqrt(s_i,0)) is at most
isolate_leak_ratio, a trial opens the valve at 1 / probe_ramp_s until the chamber holds its share
(re-admitted after readmit_hold_s with the valve at most readmit_max_opening) or the valve is
fully open and it is short (stays isolated); the proportional part tracks the
error while isolated (bumpless); (2b) several leaks flooding the reservoir together: with the fan
curve c (p_o - s) (1 - s / s_max) calibrated through the present flow of all valves, the steady
reservoir suction with a candidate set C (the k leakiest admitted chambers) given up solves
q_fan(s) = sqrt(s) sum lambda_i sqrt(k_i), k_i = min(ratio, 1 / (1 + lambda_i^2)), and the best
set is given up when its predicted F (capped at F*) beats keeping all by flood_gain_ratio for
flood_isolate_s (valves close at the trial's rate, first retry after flood_retry_initial_s, and
F_d <= flood_demand_max_ratio F* while such a chamber is isolated); (3) force loop: the demand F_d integrates F* - F with
conditional integration and back-calculation, F_d in [0, min(force_demand_max_ratio F*,
max(F*, A_admitted ratio s_R))], s_base = min(max(0, F_d - F_isolated) / A_admitted, max_suction_pa)
with F_isolated = sum over the isolated chambers of A_i max(0, s_i); (4) balance
trims b_i; (5) valve loops, velocity-form PI on e_i = min(s_base (1 - b_i), ratio s_R) - s_i:
u_i += dt k_v e_i + k_p (e_i - e_i,prev), clamped to [0, 1], after a reservoir feed-forward
u_i *= sqrt((s_R,prev - s_i) / (s_R - s_i)) (where s_i <= ratio s_R, or while the force one
command delay ahead, F + (F - F_prev) (delay + dt) / dt, is over F*) and followed by an
overshoot guard.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

VALVE_COUNT = 7  #: the default robot's chambers 1..7 (7 = centre); a robot's own count is len(chamber_area_m2)


@dataclass
class AdhesionControllerParams:
    ambient_pressure_pa: float = 100000.0  #: p_o
    chamber_area_m2: list[float] = field(default_factory=lambda: [0.0] * VALVE_COUNT)  #: A_i, one per chamber
    p_RobotChamber_m: list[tuple[float, float]] = field(default_factory=lambda: [(0.0, 0.0)] * VALVE_COUNT)
    desired_downforce_n: float = 2200.0  #: F*
    balance: bool = True
    max_suction_pa: float = 22000.0
    force_tau_s: float = 1.0
    force_demand_max_ratio: float = 1.5
    balance_tau_s: float = 1.0
    max_trim: float = 0.5
    valve_gain_per_pa_s: float = 1e-4
    valve_prop_per_pa: float = 1e-5
    overshoot_guard_ratio: float = 1.25
    reservoir_tracking_ratio: float = 0.9
    valve_full_stroke_s: float = 0.2
    valve_command_delay_s: float = 0.02
    isolate_leak_ratio: float = 1.5
    isolate_min_opening: float = 0.1
    isolate_min_reservoir_suction_pa: float = 2000.0
    isolate_delay_s: float = 0.1
    min_isolation_s: float = 0.3
    reseal_suction_ratio: float = 0.3
    retry_initial_s: float = 1.0
    retry_max_s: float = 8.0
    isolate_shortfall_ratio: float = 0.05
    isolate_saturated_s: float = 1.0
    probe_opening: float = 0.02
    probe_check_s: float = 0.3
    probe_rise_ratio: float = 0.01
    probe_ramp_s: float = 1.0
    probe_s: float = 2.0
    readmit_max_opening: float = 0.9
    readmit_tolerance_ratio: float = 0.02
    readmit_hold_s: float = 0.2
    fan_max_suction_pa: float = 22000.0
    flood_gain_ratio: float = 0.15
    flood_min_leak_ratio: float = 0.5
    flood_isolate_s: float = 1.0
    flood_retry_initial_s: float = 4.0
    flood_demand_max_ratio: float = 1.2


@dataclass
class AdhesionMeasurement:
    pressure_pa: list[float]  #: chambers 1..N, then the reservoir if the robot has one [Pa]
    downforce_n: float = 0.0  #: F [N]
    p_RobotPF_m: tuple[float, float] = (0.0, 0.0)  #: P_F in the robot frame [m]


def _clamp(v: float, lo: float, hi: float) -> float:
    return lo if v < lo else hi if v > hi else v


def _require_in(name: str, value: float, lo: float, hi: float, what: str) -> None:
    if not (math.isfinite(value) and lo <= value <= hi):
        raise ValueError(f"adhesion controller: {name} = {value} (must be in {what})")


class AdhesionController:
    def __init__(self, params: AdhesionControllerParams) -> None:
        for name in ("ambient_pressure_pa", "desired_downforce_n", "max_suction_pa", "force_tau_s",
                     "balance_tau_s", "valve_gain_per_pa_s", "valve_full_stroke_s", "isolate_leak_ratio",
                     "retry_initial_s", "probe_ramp_s", "fan_max_suction_pa", "flood_min_leak_ratio",
                     "flood_retry_initial_s"):
            value = getattr(params, name)
            if not (math.isfinite(value) and value > 0):
                raise ValueError(f"adhesion controller: {name} = {value} (must be finite and > 0)")
        if not all(math.isfinite(a) and a > 0 for a in params.chamber_area_m2):
            raise ValueError(f"adhesion controller: chamber_area_m2 = {params.chamber_area_m2} (each > 0)")
        _require_in("force_demand_max_ratio", params.force_demand_max_ratio, 1.0, 1e3, "[1, 1000]")
        _require_in("reservoir_tracking_ratio", params.reservoir_tracking_ratio, 1e-12, 1.0 - 1e-12, "(0, 1)")
        _require_in("max_trim", params.max_trim, 0.0, 1.0 - 1e-12, "[0, 1)")
        _require_in("isolate_min_opening", params.isolate_min_opening, 1e-12, 1.0, "(0, 1]")
        _require_in("isolate_min_reservoir_suction_pa", params.isolate_min_reservoir_suction_pa, 0.0, 1e9, ">= 0")
        _require_in("isolate_delay_s", params.isolate_delay_s, 0.0, 1e9, ">= 0")
        _require_in("min_isolation_s", params.min_isolation_s, 0.0, 1e9, ">= 0")
        _require_in("reseal_suction_ratio", params.reseal_suction_ratio, 1e-12, 1.0 - 1e-12, "(0, 1)")
        _require_in("retry_max_s", params.retry_max_s, params.retry_initial_s, 1e9, ">= retry_initial_s")
        _require_in("valve_command_delay_s", params.valve_command_delay_s, 0.0, 1e3, "[0, 1000]")
        _require_in("probe_rise_ratio", params.probe_rise_ratio, 1e-12, 1.0 - 1e-12, "(0, 1)")
        _require_in("isolate_shortfall_ratio", params.isolate_shortfall_ratio, 0.0, 1.0 - 1e-12, "[0, 1)")
        _require_in("isolate_saturated_s", params.isolate_saturated_s, 0.0, 1e9, ">= 0")
        _require_in("probe_check_s", params.probe_check_s, 0.0, 1e9, ">= 0")
        _require_in("readmit_max_opening", params.readmit_max_opening, 1e-12, 1.0 - 1e-12, "(0, 1)")
        _require_in("readmit_tolerance_ratio", params.readmit_tolerance_ratio, 0.0, 1.0 - 1e-12, "[0, 1)")
        _require_in("readmit_hold_s", params.readmit_hold_s, 0.0, 1e9, ">= 0")
        _require_in("probe_opening", params.probe_opening, 1e-12, 1.0, "(0, 1]")
        _require_in("probe_s", params.probe_s, 0.0, 1e9, ">= 0")
        _require_in("valve_prop_per_pa", params.valve_prop_per_pa, 0.0, 1.0, "[0, 1]")
        _require_in("overshoot_guard_ratio", params.overshoot_guard_ratio, 1.0, 1e3, "[1, 1000]")
        _require_in("flood_gain_ratio", params.flood_gain_ratio, 0.0, 1e3, "[0, 1000]")
        _require_in("flood_isolate_s", params.flood_isolate_s, 0.0, 1e9, ">= 0")
        _require_in("flood_demand_max_ratio", params.flood_demand_max_ratio, 1.0, 1e3, "[1, 1000]")
        _require_in("fan_max_suction_pa", params.fan_max_suction_pa, 1e-12,
                    params.ambient_pressure_pa * (1.0 - 1e-12), "(0, ambient_pressure_pa)")
        self.params = params
        self.n = len(params.chamber_area_m2)  #: N chambers, index i = chamber i + 1
        self.total_area_m2 = 0.0
        for a in params.chamber_area_m2:  # summed in the C++ order
            self.total_area_m2 += a
        self.force_demand_n = params.desired_downforce_n
        self.s_base_pa = min(self.force_demand_n / self.total_area_m2, params.max_suction_pa)
        self.trim = [0.0] * self.n
        self.opening = [0.0] * self.n
        self.expected_opening = [0.0] * self.n
        self.isolated = [False] * self.n
        self.flood_isolated = [False] * self.n  #: isolated by step 2b (and not re-admitted since)
        self.verdict_s = [0.0] * self.n
        self.short_s = [0.0] * self.n
        self.state_s = [0.0] * self.n
        self.retry_s = [params.retry_initial_s] * self.n
        self.probing = [False] * self.n
        self.probe_ramp = [False] * self.n  #: past the leak check: on trial, its valve opening
        self.probe_start_suction_pa = [0.0] * self.n
        self.ok_s = [0.0] * self.n
        self.last_error_pa = [0.0] * self.n
        self.last_reservoir_suction_pa = 0.0
        self.last_downforce_n = 0.0
        self.flood_s = 0.0  #: how long isolating the best candidate set has been predicted to pay [s]
        self.flood_candidates = [False] * self.n  #: the chambers step 2b would isolate now
        self.flood_predicted_n = 0.0  #: step 2b's predicted F with flood_candidates isolated [N]
        self.flood_predicted_all_n = 0.0  #: and with every admitted chamber kept [N]
        self.isolation_count = 0
        self.flood_isolation_count = 0
        self.probe_count = 0

    def set_desired_downforce(self, downforce_n: float) -> None:
        """Changes F* without resetting the loops (F_d shifts by the change)."""
        if not (math.isfinite(downforce_n) and downforce_n > 0):
            raise ValueError(f"adhesion controller: desired_downforce_n = {downforce_n} (must be finite and > 0)")
        p = self.params
        self.force_demand_n = _clamp(self.force_demand_n + (downforce_n - p.desired_downforce_n), 0.0,
                                     p.force_demand_max_ratio * downforce_n)
        p.desired_downforce_n = downforce_n

    def _suction_for(self, demand_n: float, admitted_area_m2: float, isolated_force_n: float) -> float:
        p = self.params
        if admitted_area_m2 <= 0.0:
            return p.max_suction_pa
        return min(max(0.0, demand_n - isolated_force_n) / admitted_area_m2, p.max_suction_pa)

    def _predicted_reservoir_suction(self, fan_scale: float, leak_flow_scale: float) -> float:
        """Where the calibrated fan curve c (p_o - s) (1 - s / s_max) meets G sqrt(s) (bisection)."""
        p = self.params
        lo = 0.0
        hi = p.fan_max_suction_pa
        for _ in range(48):
            mid = 0.5 * (lo + hi)
            fan = fan_scale * (p.ambient_pressure_pa - mid) * (1.0 - mid / p.fan_max_suction_pa)
            if fan > leak_flow_scale * math.sqrt(mid):
                lo = mid
            else:
                hi = mid
        return lo

    def _flood_isolation(self, m: AdhesionMeasurement, dt_s: float, reservoir_suction_pa: float,
                         isolated_before: list[bool]) -> None:
        """Step 2b: several leaks flooding the reservoir together; the set of leakiest chambers
        whose isolation the reservoir's steady flow balance predicts to pay is given up."""
        p = self.params
        self.flood_candidates = [False] * self.n
        self.flood_predicted_n = 0.0
        self.flood_predicted_all_n = 0.0
        evaluable = (self.isolated == isolated_before
                     and reservoir_suction_pa >= p.isolate_min_reservoir_suction_pa
                     and reservoir_suction_pa < p.fan_max_suction_pa
                     and m.downforce_n < (1.0 - p.isolate_shortfall_ratio) * p.desired_downforce_n)
        any_open = False
        admitted = 0
        flow = 0.0
        isolated_force_n = 0.0
        leak2 = [0.0] * self.n
        keep = [0.0] * self.n
        for i in range(self.n):
            suction_pa = p.ambient_pressure_pa - m.pressure_pa[i]
            u = self.expected_opening[i]
            flow += u * math.sqrt(max(0.0, reservoir_suction_pa - suction_pa))
            if self.isolated[i]:
                isolated_force_n += p.chamber_area_m2[i] * max(0.0, suction_pa)
                if u > p.probe_opening or self.opening[i] > p.probe_opening:
                    evaluable = False
                continue
            admitted += 1
            if u >= 1.0:
                any_open = True
            if suction_pa <= 0.0:
                evaluable = False
                continue
            leak2[i] = u * u * max(0.0, reservoir_suction_pa - suction_pa) / suction_pa
            keep[i] = min(p.reservoir_tracking_ratio, 1.0 / (1.0 + leak2[i]))
        if not (evaluable and any_open and admitted > 1 and flow > 0.0):
            self.flood_s = 0.0
            return
        fan_scale = flow / ((p.ambient_pressure_pa - reservoir_suction_pa)
                            * (1.0 - reservoir_suction_pa / p.fan_max_suction_pa))

        def predicted(out: list[bool]) -> float:
            leak_flow_scale = 0.0
            held_area_m2 = 0.0
            for i in range(self.n):
                if self.isolated[i] or out[i]:
                    continue
                leak_flow_scale += math.sqrt(leak2[i] * keep[i])
                held_area_m2 += p.chamber_area_m2[i] * keep[i]
            s_r = self._predicted_reservoir_suction(fan_scale, leak_flow_scale)
            return min(p.desired_downforce_n, isolated_force_n + s_r * held_area_m2)

        out = [False] * self.n
        all_n = predicted(out)
        best_n = all_n
        best = [False] * self.n
        min_leak2 = p.flood_min_leak_ratio * p.flood_min_leak_ratio
        for _ in range(1, admitted):
            nxt = -1
            for i in range(self.n):
                if self.isolated[i] or out[i] or leak2[i] < min_leak2:
                    continue
                if nxt < 0 or leak2[i] > leak2[nxt]:
                    nxt = i
            if nxt < 0:
                break
            out[nxt] = True
            f_n = predicted(out)
            if f_n > best_n:
                best_n = f_n
                best = list(out)
        self.flood_predicted_all_n = all_n
        self.flood_predicted_n = best_n
        self.flood_candidates = best
        self.flood_s = self.flood_s + dt_s if best_n > (1.0 + p.flood_gain_ratio) * all_n else 0.0
        if self.flood_s < p.flood_isolate_s or self.flood_s <= 0.0:
            return
        self.flood_s = 0.0
        for i in range(self.n):
            if not best[i]:
                continue
            self.isolated[i] = True
            self.flood_isolated[i] = True
            # The first retry waits until the reservoir and the others have settled.
            self.retry_s[i] = min(p.flood_retry_initial_s, p.retry_max_s)
            self.state_s[i] = 0.0
            self.verdict_s[i] = 0.0
            self.short_s[i] = 0.0
            # Its valve closes at the trial's rate (step 5): the others take its share over.
            self.probe_ramp[i] = self.opening[i] > 0.0
            self.isolation_count += 1
            self.flood_isolation_count += 1

    def step(self, m: AdhesionMeasurement, dt_s: float) -> list[float]:
        """One control period of dt_s seconds; returns the valve openings, each in [0, 1]."""
        p = self.params
        if not (math.isfinite(dt_s) and dt_s > 0):
            raise ValueError("adhesion controller: dt_s must be finite and > 0")
        values = [m.downforce_n, *m.p_RobotPF_m, *m.pressure_pa]
        if not all(math.isfinite(v) for v in values):
            raise ValueError("adhesion controller: measurement is not finite")
        reservoir_suction_pa = p.ambient_pressure_pa - m.pressure_pa[self.n]
        force_error_n = p.desired_downforce_n - m.downforce_n

        # 1. Where the valves should be by now.
        max_move = dt_s / p.valve_full_stroke_s
        for i in range(self.n):
            self.expected_opening[i] += _clamp(self.opening[i] - self.expected_opening[i], -max_move, max_move)

        # 2. Isolate a chamber whose leak its valve cannot make up; re-admit one that has re-sealed
        #    or whose probe shows that its valve can.
        ratio2 = p.isolate_leak_ratio * p.isolate_leak_ratio
        cap_pa = p.reservoir_tracking_ratio * reservoir_suction_pa
        judged = reservoir_suction_pa >= p.isolate_min_reservoir_suction_pa
        probing_any = any(self.probing)
        isolated_before = list(self.isolated)
        for i in range(self.n):
            suction_pa = p.ambient_pressure_pa - m.pressure_pa[i]
            u = self.expected_opening[i]
            # Far beyond any valve: lambda_i = u sqrt((s_R - s_i) / s_i) over isolate_leak_ratio.
            flooding = (judged and u >= p.isolate_min_opening
                        and u * u * (reservoir_suction_pa - suction_pa) > ratio2 * suction_pa)
            # The chamber's share: the common target, or its trimmed one when that is lower.
            share_pa = self.s_base_pa * min(1.0, 1.0 - self.trim[i])
            self.state_s[i] += dt_s
            if not self.isolated[i]:
                # Cannot compensate: valve fully open, the reservoir not the limit, and still short.
                short_open = (judged and u >= 1.0 and share_pa < cap_pa
                              and suction_pa < (1.0 - p.isolate_shortfall_ratio) * share_pa)
                self.verdict_s[i] = self.verdict_s[i] + dt_s if flooding else 0.0
                self.short_s[i] = self.short_s[i] + dt_s if short_open else 0.0
                if ((flooding and self.verdict_s[i] >= p.isolate_delay_s)
                        or (short_open and self.short_s[i] >= p.isolate_saturated_s)):
                    self.isolated[i] = True
                    self.retry_s[i] = p.retry_initial_s
                    self.state_s[i] = 0.0
                    self.verdict_s[i] = 0.0
                    self.short_s[i] = 0.0
                    self.opening[i] = 0.0
                    self.isolation_count += 1
            elif self.probing[i] and not self.probe_ramp[i]:
                # Leak check: holds, or answers the probe's small flow with a rise only a nearly
                # sealed chamber gives: re-admitted at once, bumpless from the probe's opening.
                holds = suction_pa >= p.reseal_suction_ratio * self.s_base_pa
                rises = (judged and suction_pa - self.probe_start_suction_pa[i]
                         >= p.probe_rise_ratio * reservoir_suction_pa)
                if holds or rises:
                    self.probing[i] = False
                    probing_any = False
                    self.isolated[i] = False
                    self.state_s[i] = 0.0
                elif self.state_s[i] >= p.probe_check_s:
                    # Else a trial if lambda = u sqrt(s_R - s_i) / (sqrt(s_i) - sqrt(s_i,0)) is not
                    # far beyond the valve.
                    rise_pa = math.sqrt(max(0.0, suction_pa)) - math.sqrt(max(0.0, self.probe_start_suction_pa[i]))
                    if (judged and rise_pa > 0.0
                            and u * u * (reservoir_suction_pa - suction_pa) <= ratio2 * rise_pa * rise_pa):
                        self.probe_ramp[i] = True  # step 5 opens the valve from the probe's opening
                        self.ok_s[i] = 0.0
                    else:
                        self.probing[i] = False
                        probing_any = False
                        self.state_s[i] = 0.0
                        self.retry_s[i] = min(2.0 * self.retry_s[i], p.retry_max_s)
                        self.opening[i] = 0.0
            elif self.probing[i]:
                # Trial: re-admitted when it holds its share with the valve at most
                # readmit_max_opening; not when fully open and short, flooding, or too long.
                target_pa = min(share_pa, cap_pa)
                on_target = suction_pa >= (1.0 - p.readmit_tolerance_ratio) * target_pa
                self.ok_s[i] = self.ok_s[i] + dt_s if on_target and u <= p.readmit_max_opening else 0.0
                if self.ok_s[i] >= p.readmit_hold_s:
                    self.probing[i] = False  # re-admitted, bumpless from the trial's opening
                    self.probe_ramp[i] = False
                    probing_any = False
                    self.isolated[i] = False
                    self.state_s[i] = 0.0
                elif flooding or (u >= 1.0 and not on_target) or self.state_s[i] >= p.probe_s:
                    # Its valve cannot make the leak up: retries later. The valve closes at the
                    # trial's rate (step 5), at once when the leak floods.
                    self.probing[i] = False
                    self.probe_ramp[i] = not flooding
                    probing_any = False
                    self.state_s[i] = 0.0
                    self.retry_s[i] = min(2.0 * self.retry_s[i], p.retry_max_s)
                    if flooding:
                        self.opening[i] = 0.0
            elif self.probe_ramp[i]:
                pass  # closing after a failed trial: its suction says nothing about a re-seal yet
            elif self.state_s[i] >= p.min_isolation_s:
                if suction_pa >= p.reseal_suction_ratio * self.s_base_pa:
                    self.isolated[i] = False  # re-sealed; the valve loop starts from the closed valve
                    self.state_s[i] = 0.0
                elif self.state_s[i] >= self.retry_s[i] and not probing_any:
                    self.probing[i] = True
                    self.probe_ramp[i] = False
                    probing_any = True
                    self.state_s[i] = 0.0
                    self.opening[i] = p.probe_opening
                    self.probe_start_suction_pa[i] = suction_pa
                    self.probe_count += 1

        # 2b. Several leaks flooding the reservoir together.
        self._flood_isolation(m, dt_s, reservoir_suction_pa, isolated_before)

        # 3. Force loop on the admitted area.
        admitted_area_m2 = 0.0
        isolated_force_n = 0.0  # what the isolated chambers pull by themselves
        for i in range(self.n):
            if not self.isolated[i]:
                admitted_area_m2 += p.chamber_area_m2[i]
            else:
                isolated_force_n += p.chamber_area_m2[i] * max(0.0, p.ambient_pressure_pa - m.pressure_pa[i])
        s_now = self._suction_for(self.force_demand_n, admitted_area_m2, isolated_force_n)
        can_pull_harder = any(not self.isolated[i] and self.opening[i] < 1.0 and s_now * (1.0 - self.trim[i]) < cap_pa
                              for i in range(self.n))
        if force_error_n < 0.0 or can_pull_harder:
            self.force_demand_n += dt_s * force_error_n / p.force_tau_s
        # Back-calculation: beyond F* the demand never exceeds what the admitted chambers give at the cap.
        # While chambers given up by step 2b are isolated, F_d stays within flood_demand_max_ratio F*.
        flood_isolated_any = False
        for i in range(self.n):
            self.flood_isolated[i] = self.flood_isolated[i] and self.isolated[i]
            flood_isolated_any = flood_isolated_any or self.flood_isolated[i]
        demand_max_ratio = (min(p.force_demand_max_ratio, p.flood_demand_max_ratio) if flood_isolated_any
                            else p.force_demand_max_ratio)
        achievable_n = max(p.desired_downforce_n, admitted_area_m2 * cap_pa)
        self.force_demand_n = _clamp(self.force_demand_n, 0.0,
                                     min(demand_max_ratio * p.desired_downforce_n, achievable_n))
        self.s_base_pa = self._suction_for(self.force_demand_n, admitted_area_m2, isolated_force_n)

        # 4. and 5. Balance trims and valve loops of the admitted chambers.
        overshooting = m.downforce_n > p.overshoot_guard_ratio * p.desired_downforce_n
        # F where it will be when a command given now acts (a sample and the command delay ahead).
        force_ahead_n = m.downforce_n + (m.downforce_n - self.last_downforce_n) * (p.valve_command_delay_s + dt_s) / dt_s
        for i in range(self.n):
            if self.isolated[i]:
                if not self.probing[i] and self.probe_ramp[i]:
                    self.opening[i] = max(0.0, self.opening[i] - dt_s / p.probe_ramp_s)  # closing after a failed trial
                    self.probe_ramp[i] = self.opening[i] > 0.0
                elif not self.probing[i]:
                    self.opening[i] = 0.0
                elif not self.probe_ramp[i]:
                    self.opening[i] = p.probe_opening
                elif self.ok_s[i] <= 0.0:
                    self.opening[i] = min(1.0, self.opening[i] + dt_s / p.probe_ramp_s)  # trial: open until it holds
                # The error it would have, so that re-admission brings no proportional kick.
                self.last_error_pa[i] = (min(self.s_base_pa * (1.0 - self.trim[i]), cap_pa)
                                         - (p.ambient_pressure_pa - m.pressure_pa[i]))
                continue
            cx, cy = p.p_RobotChamber_m[i]
            r_m = math.hypot(cx, cy)
            if p.balance and r_m > 1e-9:
                towards = (m.p_RobotPF_m[0] * cx + m.p_RobotPF_m[1] * cy) / (r_m * r_m)
                saturated = self.opening[i] >= 1.0 and towards < 0.0
                if not saturated:
                    self.trim[i] = _clamp(self.trim[i] + dt_s * towards / p.balance_tau_s, -p.max_trim, p.max_trim)
            else:
                self.trim[i] = 0.0
            target_pa = min(self.s_base_pa * (1.0 - self.trim[i]), cap_pa)
            suction_pa = p.ambient_pressure_pa - m.pressure_pa[i]
            # Reservoir feed-forward: the same valve flow needs a smaller opening when s_R rises;
            # above the cap (ill-conditioned) only while F is heading over F*.
            if (reservoir_suction_pa > suction_pa and self.last_reservoir_suction_pa > suction_pa
                    and (suction_pa <= cap_pa or force_ahead_n >= p.desired_downforce_n)):
                self.opening[i] = min(1.0, self.opening[i] * math.sqrt((self.last_reservoir_suction_pa - suction_pa)
                                                                       / (reservoir_suction_pa - suction_pa)))
            error_pa = target_pa - suction_pa
            self.opening[i] = _clamp(self.opening[i] + dt_s * p.valve_gain_per_pa_s * error_pa
                                     + p.valve_prop_per_pa * (error_pa - self.last_error_pa[i]), 0.0, 1.0)
            self.last_error_pa[i] = error_pa
            # Overshoot guard: deeper than its target, at most the opening that would hold the target
            # with the present leak, u* = u^ sqrt((s_R - s_i) s* / (s_i (s_R - s*))).
            if overshooting and suction_pa > target_pa:
                guard = 0.0
                if target_pa > 0.0 and reservoir_suction_pa > suction_pa and reservoir_suction_pa > target_pa:
                    guard = self.expected_opening[i] * math.sqrt(((reservoir_suction_pa - suction_pa) * target_pa)
                                                                 / (suction_pa * (reservoir_suction_pa - target_pa)))
                self.opening[i] = min(self.opening[i], guard)
        self.last_reservoir_suction_pa = reservoir_suction_pa
        self.last_downforce_n = m.downforce_n
        return list(self.opening)
