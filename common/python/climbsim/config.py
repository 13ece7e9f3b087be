"""What a controller needs of a scenario file (deploy/scenarios/*.yaml) and its robot file
(deploy/robots/*.yaml), as the C++ controller has validated it.

The files have one validation: the C++ loaders (loadScenario, loadRobotDescription), with their
`file:line: key = value: why` messages. This module does not parse the files; it runs
`climbsim-controller --scenario FILE --print-config`, which validates them and prints the
controller's configuration as JSON (services/controller/client_config.hpp): the same values,
bit for bit, that the C++ controller runs with. A file the C++ side refuses is a ConfigError
with the C++ message."""

from __future__ import annotations

import json
import math
import os
import re
import shutil
import subprocess
from dataclasses import dataclass, field
from pathlib import Path

from .dds import ConfigError

#: The C++ controller that validates the files (CLIMBSIM_BIN_DIR: the build's bin/, which the
#: wrappers in <build>/bin set; else the PATH).
CONTROLLER_PROGRAM = "climbsim-controller"


@dataclass(frozen=True)
class DriveCommand:
    """A body-frame drive command from t_s on."""

    t_s: float = 0.0
    vx_mps: float = 0.0
    vy_mps: float = 0.0
    wz_radps: float = 0.0


@dataclass
class Scenario:
    """The controller's part of a validated scenario and its robot."""

    source: Path
    name: str
    controller_type: str  #: none, fixed, reference, external
    valves: list[float]  #: fixed openings, one per chamber (type fixed)
    engine_count: int  #: the robot's engines
    drive: list[DriveCommand] = field(default_factory=list)
    #: Keyword arguments of AdhesionControllerParams that the scenario and the robot set
    #: (chamber areas and centroids, p_o, F* with the scenario's set-point applied, balance,
    #: max suction, valve stroke and delay), as the C++ controller uses them.
    reference: dict = field(default_factory=dict)
    chamber_count: int = 7  #: N
    has_reservoir: bool = True  #: valves on a reservoir; else the engines pump the chambers directly
    #: Keyword arguments of EngineControllerParams (every field; the reference controller on a
    #: robot without a reservoir), as the C++ controller uses them.
    engine_reference: dict = field(default_factory=dict)


def _program() -> str:
    bin_dir = os.environ.get("CLIMBSIM_BIN_DIR")
    if bin_dir and os.access(Path(bin_dir) / CONTROLLER_PROGRAM, os.X_OK):
        return str(Path(bin_dir) / CONTROLLER_PROGRAM)
    found = shutil.which(CONTROLLER_PROGRAM)
    if found is None:
        raise ConfigError(f"{CONTROLLER_PROGRAM} not found (set CLIMBSIM_BIN_DIR to the build's bin/): it validates "
                          "the scenario and robot files")
    return found


def _cpp_errors(stderr: str) -> list[str]:
    """The messages of the C++ error lines ("HH:MM:SS.mmm NAME error: MESSAGE")."""
    return [m.group(1) for m in re.finditer(r"^\S+ \S+ error: (.*)$", stderr, re.M)]


def load_scenario(path: str | Path, overrides: list[str] | tuple[str, ...] = ()) -> Scenario:
    """The scenario `path` (with `--set` overrides) and its robot, validated by the C++ loaders."""
    path = Path(path)
    command = [_program(), "--name", "controller-config", "--scenario", str(path), "--print-config"]
    for o in overrides:
        command += ["--set", o]
    env = dict(os.environ, CLIMBSIM_LOG_LEVEL="error")
    done = subprocess.run(command, capture_output=True, text=True, env=env, check=False)
    if done.returncode != 0:
        errors = _cpp_errors(done.stderr) or [done.stderr.strip() or f"{command[0]} exited {done.returncode}"]
        raise ConfigError("\n".join(errors))
    c = json.loads(done.stdout)
    reference = dict(c["reference"])
    reference["p_RobotChamber_m"] = [tuple(p) for p in reference["p_RobotChamber_m"]]
    engine_reference = dict(c["engine_reference"])
    engine_reference["p_RobotChamber_m"] = [tuple(p) for p in engine_reference["p_RobotChamber_m"]]
    return Scenario(source=path, name=c["scenario"], controller_type=c["controller"], valves=list(c["fixed_valves"]),
                    engine_count=int(c["engine_count"]), drive=[DriveCommand(**d) for d in c["drive"]],
                    reference=reference, chamber_count=int(c["chamber_count"]), has_reservoir=bool(c["has_reservoir"]),
                    engine_reference=engine_reference)


def drive_command_at(schedule: list[DriveCommand], t_ns: int) -> DriveCommand:
    """The last command whose time has come (round(t_s * 1e9) <= t_ns)."""
    current = DriveCommand()
    for cmd in schedule:
        if math.floor(cmd.t_s * 1e9 + 0.5) > t_ns:  # llround for t_s >= 0
            break
        current = cmd
    return current
