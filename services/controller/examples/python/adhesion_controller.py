"""The reference adhesion controller in Python: a line-by-line port of
services/controller/model/adhesion_controller.cpp (same loops, same order of operations, so
the same numbers up to floating-point summation order). Pure Python: no DDS.

Three loops, all with integral action and anti-windup:
 - force loop: the common suction target s_base [Pa] (s = p_o - p) integrates the force error,
       d s_base / dt = (F* - F) / (sum_i A_i * force_tau_s),   s_base in [0, max_suction_pa];
 - balance loop (ring chambers, when enabled): a per-chamber trim b_i integrates how far P_F
   lies towards chamber i,  d b_i / dt = (P_F . u_i) / (r_i * balance_tau_s),  |b_i| <= max_trim;
 - valve loop: d u_i / dt = valve_gain_per_pa_s * (min(s_base (1 - b_i), ratio * s_R) - s_i),
   u_i in [0, 1].
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

VALVE_COUNT = 7  #: chambers 1..7, index i = chamber i + 1 (7 = centre)


@dataclass
class AdhesionControllerParams:
    ambient_pressure_pa: float = 100000.0  #: p_o
    chamber_area_m2: list[float] = field(default_factory=lambda: [0.0] * VALVE_COUNT)  #: A_i
    p_RobotChamber_m: list[tuple[float, float]] = field(default_factory=lambda: [(0.0, 0.0)] * VALVE_COUNT)
    desired_downforce_n: float = 2200.0  #: F*
    balance: bool = True
    max_suction_pa: float = 22000.0
    force_tau_s: float = 1.0
    balance_tau_s: float = 1.0
    max_trim: float = 0.5
    valve_gain_per_pa_s: float = 1e-4
    reservoir_tracking_ratio: float = 0.9


@dataclass
class AdhesionMeasurement:
    pressure_pa: list[float]  #: chambers 1..7, then the reservoir [Pa]
    downforce_n: float = 0.0  #: F [N]
    p_RobotPF_m: tuple[float, float] = (0.0, 0.0)  #: P_F in the robot frame [m]


def _clamp(v: float, lo: float, hi: float) -> float:
    return lo if v < lo else hi if v > hi else v


class AdhesionController:
    def __init__(self, params: AdhesionControllerParams) -> None:
        for name in ("ambient_pressure_pa", "desired_downforce_n", "max_suction_pa", "force_tau_s",
                     "balance_tau_s", "valve_gain_per_pa_s"):
            value = getattr(params, name)
            if not (math.isfinite(value) and value > 0):
                raise ValueError(f"adhesion controller: {name} = {value} (must be finite and > 0)")
        if not all(math.isfinite(a) and a > 0 for a in params.chamber_area_m2):
            raise ValueError(f"adhesion controller: chamber_area_m2 = {params.chamber_area_m2} (each > 0)")
        if not 0.0 < params.reservoir_tracking_ratio < 1.0:
            raise ValueError(f"adhesion controller: reservoir_tracking_ratio = {params.reservoir_tracking_ratio}")
        if not 0.0 <= params.max_trim < 1.0:
            raise ValueError(f"adhesion controller: max_trim = {params.max_trim} (must be in [0, 1))")
        self.params = params
        self.total_area_m2 = 0.0
        for a in params.chamber_area_m2:  # summed in the C++ order
            self.total_area_m2 += a
        self.s_base_pa = _clamp(params.desired_downforce_n / self.total_area_m2, 0.0, params.max_suction_pa)
        self.trim = [0.0] * VALVE_COUNT
        self.opening = [0.0] * VALVE_COUNT

    def step(self, m: AdhesionMeasurement, dt_s: float) -> list[float]:
        """One control period of dt_s seconds; returns the valve openings, each in [0, 1]."""
        p = self.params
        if not (math.isfinite(dt_s) and dt_s > 0):
            raise ValueError("adhesion controller: dt_s must be finite and > 0")
        values = [m.downforce_n, *m.p_RobotPF_m, *m.pressure_pa]
        if not all(math.isfinite(v) for v in values):
            raise ValueError("adhesion controller: measurement is not finite")
        reservoir_suction_pa = p.ambient_pressure_pa - m.pressure_pa[VALVE_COUNT]
        force_error_n = p.desired_downforce_n - m.downforce_n
        if not (force_error_n > 0.0 and reservoir_suction_pa <= self.s_base_pa):
            self.s_base_pa = _clamp(self.s_base_pa + dt_s * force_error_n / (self.total_area_m2 * p.force_tau_s),
                                    0.0, p.max_suction_pa)
        for i in range(VALVE_COUNT):
            cx, cy = p.p_RobotChamber_m[i]
            r_m = math.hypot(cx, cy)
            if p.balance and r_m > 1e-9:
                towards = (m.p_RobotPF_m[0] * cx + m.p_RobotPF_m[1] * cy) / (r_m * r_m)
                saturated = self.opening[i] >= 1.0 and towards < 0.0
                if not saturated:
                    self.trim[i] = _clamp(self.trim[i] + dt_s * towards / p.balance_tau_s, -p.max_trim, p.max_trim)
            else:
                self.trim[i] = 0.0
            target_pa = min(self.s_base_pa * (1.0 - self.trim[i]), p.reservoir_tracking_ratio * reservoir_suction_pa)
            suction_pa = p.ambient_pressure_pa - m.pressure_pa[i]
            self.opening[i] = _clamp(self.opening[i] + dt_s * p.valve_gain_per_pa_s * (target_pa - suction_pa),
                                     0.0, 1.0)
        return list(self.opening)
