"""The parts of a scenario file (deploy/scenarios/*.yaml) and a robot file
(deploy/robots/*.yaml) that a controller needs, and the chamber geometry of the robot
(as climbsim::computeGeometry, common/src/robot/robot_geometry.cpp). The C++ loaders validate
these files fully; here a missing or wrong key is a ConfigError naming the file and key."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import yaml

from .dds import ConfigError


@dataclass(frozen=True)
class DriveCommand:
    """A body-frame drive command from t_s on."""

    t_s: float = 0.0
    vx_mps: float = 0.0
    vy_mps: float = 0.0
    wz_radps: float = 0.0


@dataclass(frozen=True)
class Chamber:
    number: int  #: 1..7 (7 = centre)
    area_m2: float  #: suction area A_i
    centroid_m: tuple[float, float]  #: P_i in the robot frame (x, y)


@dataclass
class Robot:
    name: str
    ambient_pressure_pa: float
    desired_downforce_n: float
    engine_count: int
    engine_dp_max_pa: float
    chambers: list[Chamber]


@dataclass
class Scenario:
    source: Path
    name: str
    controller_type: str  #: none, fixed, reference, external
    downforce_n: float | None
    balance: bool
    valves: list[float]  #: fixed openings (type fixed)
    drive: list[DriveCommand] = field(default_factory=list)
    robot: Robot | None = None


def _load(path: Path) -> dict:
    try:
        data = yaml.safe_load(path.read_text())
    except OSError as e:
        raise ConfigError(f"{path}: cannot read it ({e.strerror})") from None
    except yaml.YAMLError as e:
        raise ConfigError(f"{path}: not valid YAML: {e}") from None
    if not isinstance(data, dict):
        raise ConfigError(f"{path}: the file must hold a mapping")
    return data


def _get(path: Path, node: dict, key: str, kind=float, default=None):
    parts = key.split(".")
    value = node
    for p in parts:
        if not isinstance(value, dict) or p not in value:
            if default is not None:
                return default
            raise ConfigError(f"{path}: key '{key}' is missing")
        value = value[p]
    try:
        if kind is bool:
            if not isinstance(value, bool):
                raise ValueError
            return value
        out = kind(value)
    except (TypeError, ValueError):
        raise ConfigError(f"{path}: key '{key}' = {value!r} is not a {kind.__name__}") from None
    if kind is float and not math.isfinite(out):
        raise ConfigError(f"{path}: key '{key}' = {value!r} is not finite")
    return out


def chamber_geometry(outer_count: int, centre_radius_m: float, sealed_diameter_m: float) -> list[Chamber]:
    """Ring sectors 1..n (chamber 1 centred on +x, counter-clockwise) and the centre disc."""
    theta = 2.0 * math.pi / outer_count
    r1 = centre_radius_m
    r2 = sealed_diameter_m / 2.0
    half = theta / 2.0
    centroid_r = 2.0 / 3.0 * (r2 * r2 * r2 - r1 * r1 * r1) / (r2 * r2 - r1 * r1) * math.sin(half) / half
    chambers = []
    for number in range(1, outer_count + 1):
        angle = (number - 1) * theta
        chambers.append(Chamber(number, theta / 2.0 * (r2 * r2 - r1 * r1),
                                (centroid_r * math.cos(angle), centroid_r * math.sin(angle))))
    chambers.append(Chamber(outer_count + 1, math.pi * r1 * r1, (0.0, 0.0)))
    return chambers


def load_robot(path: Path) -> Robot:
    d = _load(path)
    outer = _get(path, d, "chambers.outer_count", int)
    if outer < 3:
        raise ConfigError(f"{path}: key 'chambers.outer_count' = {outer}; it must be >= 3")
    return Robot(
        name=str(d.get("name", path.stem)),
        ambient_pressure_pa=_get(path, d, "gas.ambient_pressure_pa"),
        desired_downforce_n=_get(path, d, "adhesion.desired_downforce_n"),
        engine_count=_get(path, d, "engines.count", int),
        engine_dp_max_pa=_get(path, d, "engines.dp_max_pa"),
        chambers=chamber_geometry(outer, _get(path, d, "chambers.centre_radius_m"),
                                  _get(path, d, "body.sealed_diameter_m")),
    )


def load_scenario(path: str | Path) -> Scenario:
    """The scenario and its robot (robot path relative to the scenario file)."""
    path = Path(path)
    d = _load(path)
    c = d.get("controller")
    if not isinstance(c, dict):
        raise ConfigError(f"{path}: key 'controller' is missing or not a mapping")
    kind = str(c.get("type", ""))
    if kind not in ("none", "fixed", "reference", "external"):
        raise ConfigError(f"{path}: key 'controller.type' = '{kind}'; it must be none, fixed, reference or external")
    drive_nodes = d.get("drive")
    if not isinstance(drive_nodes, list) or not drive_nodes:
        raise ConfigError(f"{path}: key 'drive' must be a list of {{t_s, vx_mps, vy_mps, wz_radps}}")
    drive: list[DriveCommand] = []
    held = DriveCommand()
    for i, e in enumerate(drive_nodes):
        key = f"drive[{i}]"
        if not isinstance(e, dict):
            raise ConfigError(f"{path}: key '{key}' must be a mapping")
        held = DriveCommand(_get(path, e, "t_s"),
                            float(e.get("vx_mps", held.vx_mps)), float(e.get("vy_mps", held.vy_mps)),
                            float(e.get("wz_radps", held.wz_radps)))
        drive.append(held)
    robot_file = Path(str(d.get("robot", "")))
    if not str(robot_file):
        raise ConfigError(f"{path}: key 'robot' is missing")
    if not robot_file.is_absolute():
        robot_file = path.parent / robot_file
    valves = [float(v) for v in c.get("valves", [])] if kind == "fixed" else []
    return Scenario(path, str(d.get("name", path.stem)), kind,
                    float(c["downforce_n"]) if "downforce_n" in c else None,
                    bool(c.get("balance", True)), valves, drive, load_robot(robot_file))


def drive_command_at(schedule: list[DriveCommand], t_ns: int) -> DriveCommand:
    """The last command whose time has come (round(t_s * 1e9) <= t_ns)."""
    current = DriveCommand()
    for cmd in schedule:
        if math.floor(cmd.t_s * 1e9 + 0.5) > t_ns:  # llround for t_s >= 0
            break
        current = cmd
    return current
