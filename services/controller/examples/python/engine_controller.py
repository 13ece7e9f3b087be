"""The reference controller's engine law in Python (robots without a reservoir): a line-by-line
port of services/controller/model/engine_controller.cpp (same operations in the same order, so
the same numbers bit for bit; the header there has the equations and docs/controllers.md the
law in short). Pure Python: no DDS.

Per step: (1) F_u = sum of A_i max(0, s_i) over the chambers no engine pumps; (2) balance trims
b_i of the pumped chambers off the centre, d b_i/dt = (P_F . P_i) / (r_i^2 balance_tau_s), held
while every engine on the chamber runs at full speed and the trim would ask for more; (3) shares
s*_i = min(s_F (1 - b_i), s_max), s_F = max(0, F* - F_u) / sum A_i (1 - b_i); (4) per engine k on
chamber c: e_k = (s*_c - s_c) / s_max, omega_ff = sqrt(s*_c / s_max),
omega_k += (omega_ff - omega_ff,prev) + K_P (e_k - e_k,prev) + dt e_k / tau_I, clamped to [0, 1].
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from adhesion_controller import AdhesionMeasurement, _clamp


@dataclass
class EngineControllerParams:
    ambient_pressure_pa: float = 100000.0  #: p_o
    chamber_area_m2: list[float] = field(default_factory=list)  #: A_i, one per chamber
    p_RobotChamber_m: list[tuple[float, float]] = field(default_factory=list)  #: centroids P_i [m]
    engine_chamber: list[int] = field(default_factory=list)  #: c_k: chamber index 0..N-1 of each engine
    desired_downforce_n: float = 700.0  #: F*
    balance: bool = True
    max_suction_pa: float = 15000.0  #: s_max (engines.dp_max_pa)
    engine_integral_s: float = 0.3  #: tau_I (engines.speed_lag_s)
    engine_prop: float = 1.0  #: K_P
    balance_tau_s: float = 1.0
    max_trim: float = 0.5


class EngineController:
    """The engine law's state and step (EngineController and EngineControllerState in C++)."""

    def __init__(self, params: EngineControllerParams) -> None:
        n = len(params.chamber_area_m2)
        if not 1 <= n <= 24 or len(params.p_RobotChamber_m) != n:
            raise ValueError(f"engine controller: {n} chamber areas and {len(params.p_RobotChamber_m)} centroids "
                             "(must be 1..24, one each per chamber)")
        if not 1 <= len(params.engine_chamber) <= 16:
            raise ValueError(f"engine controller: {len(params.engine_chamber)} engines (must be 1..16)")
        for k, c in enumerate(params.engine_chamber):
            if not 0 <= c < n:
                raise ValueError(f"engine controller: engine {k + 1} pumps chamber {c + 1} (the robot has chambers "
                                 f"1..{n})")
        for name in ("ambient_pressure_pa", "desired_downforce_n", "max_suction_pa", "engine_integral_s",
                     "balance_tau_s"):
            value = getattr(params, name)
            if not (math.isfinite(value) and value > 0):
                raise ValueError(f"engine controller: {name} = {value} (must be finite and > 0)")
        self.params = params
        self.pumped = [i in params.engine_chamber for i in range(n)]
        self.trim = [0.0] * n  #: b_i
        self.target_pa = [0.0] * n  #: s*_i of the last step
        engines = len(params.engine_chamber)
        self.speed = [0.0] * engines  #: omega_k, the commanded speeds
        self.last_error = [0.0] * engines
        self.last_feedforward = [0.0] * engines

    def step(self, m: AdhesionMeasurement, dt_s: float) -> list[float]:
        """The engines' speeds for one period of dt_s [s] from the measurement (N pressures)."""
        p = self.params
        n = len(p.chamber_area_m2)
        if len(m.pressure_pa) != n:
            raise ValueError(f"engine controller: {len(m.pressure_pa)} pressures for {n} chambers (no reservoir)")
        # 1. What the chambers without an engine pull by themselves.
        unpumped_force_n = 0.0
        for i in range(n):
            if not self.pumped[i]:
                unpumped_force_n += p.chamber_area_m2[i] * max(0.0, p.ambient_pressure_pa - m.pressure_pa[i])
        # 2. Balance trims of the pumped chambers off the centre.
        for i in range(n):
            cx, cy = p.p_RobotChamber_m[i]
            r2_m2 = cx * cx + cy * cy
            if not p.balance or not self.pumped[i] or r2_m2 <= 1e-18:
                self.trim[i] = 0.0
                continue
            towards = (m.p_RobotPF_m[0] * cx + m.p_RobotPF_m[1] * cy) / r2_m2
            saturated = towards < 0.0
            for k, c in enumerate(p.engine_chamber):
                if c == i:
                    saturated = saturated and self.speed[k] >= 1.0
            if not saturated:
                self.trim[i] = _clamp(self.trim[i] + dt_s * towards / p.balance_tau_s, -p.max_trim, p.max_trim)
        # 3. The pumped chambers' shares of F*.
        weighted_area_m2 = 0.0
        for i in range(n):
            if self.pumped[i]:
                weighted_area_m2 += p.chamber_area_m2[i] * (1.0 - self.trim[i])
        common_pa = max(0.0, p.desired_downforce_n - unpumped_force_n) / weighted_area_m2
        for i in range(n):
            self.target_pa[i] = min(common_pa * (1.0 - self.trim[i]), p.max_suction_pa) if self.pumped[i] else 0.0
        # 4. Each engine's PI on its chamber's normalised error, with the fan curve's feed-forward.
        for k, c in enumerate(p.engine_chamber):
            target_pa = self.target_pa[c]
            error = (target_pa - (p.ambient_pressure_pa - m.pressure_pa[c])) / p.max_suction_pa
            feedforward = math.sqrt(target_pa / p.max_suction_pa)
            self.speed[k] = _clamp(self.speed[k] + (feedforward - self.last_feedforward[k])
                                   + p.engine_prop * (error - self.last_error[k]) + dt_s * error / p.engine_integral_s,
                                   0.0, 1.0)
            self.last_error[k] = error
            self.last_feedforward[k] = feedforward
        return list(self.speed)
