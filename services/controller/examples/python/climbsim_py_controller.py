"""climbsim-py-controller: the scenario's controller in Python on Cyclone DDS, a roster member
of the lockstep clock in place of climbsim-controller (deploy/compose.python-controller.yaml).

Reads ChamberState and AdhesionForce; writes ValveCommand (unless the scenario's controller is
external), EngineCommand (engines on at full speed, or at the engine law's speeds on a robot
without a reservoir; not for external there) and the scenario's DriveCommand schedule every due
step: the behaviour of services/controller (node/controller_node.cpp, main.cpp).

    climbsim-py-controller --scenario FILE --name controller [--period N --offset K] --domain D
"""

from __future__ import annotations

import argparse
import logging
import math
import sys

import climbsim_idl as idl
from climbsim import topics
from climbsim.config import drive_command_at, load_scenario
from climbsim.dds import ConfigError
from climbsim.lockstep import EXIT_CONFIG, LockstepParticipant, add_participant_options

from adhesion_controller import AdhesionController, AdhesionControllerParams, AdhesionMeasurement
from engine_controller import EngineController, EngineControllerParams

log = logging.getLogger("climbsim")


class ControllerNode:
    """Input holding and command logic per scenario controller type (as ControllerNode)."""

    def __init__(self, scenario) -> None:
        # The scenario and robot as the C++ controller validated them (climbsim.config).
        self.kind = scenario.controller_type
        self.fixed_valves = scenario.valves
        self.drive = scenario.drive
        self.engine_count = scenario.engine_count
        self.dropped = 0
        self.has_reservoir = scenario.has_reservoir
        params = AdhesionControllerParams(**scenario.reference)
        self.chambers = scenario.chamber_count  #: N: one valve per chamber on a reservoir
        self.volumes = self.chambers + (1 if self.has_reservoir else 0)  #: pressures: the reservoir's last
        self.measured = AdhesionMeasurement(pressure_pa=[params.ambient_pressure_pa] * self.volumes)
        reference = self.kind == "reference"
        self.reference = AdhesionController(params) if reference and self.has_reservoir else None
        self.engine_reference = (EngineController(EngineControllerParams(**scenario.engine_reference))
                                 if reference and not self.has_reservoir else None)

    def commands_valves(self) -> bool:
        return self.kind != "external"

    def commands_engines(self) -> bool:
        """The engines are the external client's where they hold the downforce (no reservoir)."""
        return self.commands_valves() or self.has_reservoir

    def step(self, t_ns: int, dt_ns: int, states, forces):
        for s in states:
            if len(s.pressure_pa) != self.volumes:
                self.dropped += 1
                log.warning("controller: dropped thermo/ChamberState from %s at step %d: %d pressures, the robot has %d "
                            "volumes", s.source, s.step, len(s.pressure_pa), self.volumes)
                continue
            if not all(math.isfinite(p) for p in s.pressure_pa):
                self.dropped += 1
                log.warning("controller: dropped ChamberState from %s at step %d: a pressure is not finite",
                            s.source, s.step)
                continue
            self.measured.pressure_pa = list(s.pressure_pa)
        for f in forces:
            if not all(math.isfinite(v) for v in (f.downforce_n, f.pf_x_m, f.pf_y_m)):
                self.dropped += 1
                log.warning("controller: dropped AdhesionForce from %s at step %d: a value is not finite",
                            f.source, f.step)
                continue
            self.measured.downforce_n = f.downforce_n
            self.measured.p_RobotPF_m = (f.pf_x_m, f.pf_y_m)
        openings = [0.0] * (self.chambers if self.has_reservoir else 0)  # one per valve: none without a reservoir
        if self.kind == "fixed":
            openings = list(self.fixed_valves)
        elif self.reference is not None:
            openings = self.reference.step(self.measured, 1e-9 * dt_ns)
        # The set-point in force (as the C++ node: 0 for none and fixed): the trace and the plots show it.
        setpoint_n = self.reference.params.desired_downforce_n if self.reference else 0.0
        speeds = [1.0] * self.engine_count
        if self.engine_reference is not None:
            speeds = self.engine_reference.step(self.measured, 1e-9 * dt_ns)
            setpoint_n = self.engine_reference.params.desired_downforce_n
        valves = idl.ValveCommand(opening=openings, downforce_setpoint_n=setpoint_n) if self.commands_valves() else None
        engines = (idl.EngineCommand(engines=[idl.EngineSetting(on=True, speed=s) for s in speeds])
                   if self.commands_engines() else None)
        cmd = drive_command_at(self.drive, t_ns)
        drive = idl.DriveCommand(vx_mps=cmd.vx_mps, vy_mps=cmd.vy_mps, wz_radps=cmd.wz_radps)
        return valves, engines, drive


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="climbsim-py-controller", description=__doc__.split("\n\n")[0])
    add_participant_options(parser)
    parser.add_argument("--scenario", required=True, help="scenario file (deploy/scenarios/*.yaml)")
    args = parser.parse_args(argv)
    # Like the C++ services' spdlog lines: "11:35:04.880 controller info: ...".
    logging.basicConfig(level=logging.INFO, datefmt="%H:%M:%S",
                        format=f"%(asctime)s.%(msecs)03d {args.name} %(levelname)s: %(message)s")
    for level in (logging.INFO, logging.WARNING, logging.ERROR):
        logging.addLevelName(level, logging.getLevelName(level).lower().replace("warning", "warn"))
    try:
        scenario = load_scenario(args.scenario)
        node = ControllerNode(scenario)
        participant = LockstepParticipant.from_args(args)
    except (ConfigError, ValueError) as e:
        print(f"climbsim-py-controller: error: {e}", file=sys.stderr)
        return EXIT_CONFIG
    log.info("controller: %s controller (Python, Cyclone DDS), scenario %s", node.kind, scenario.name)
    states = participant.input(topics.CHAMBER_STATE, idl.ChamberState)
    forces = participant.input(topics.ADHESION_FORCE, idl.AdhesionForce)
    valves = participant.output(topics.VALVE_COMMAND, idl.ValveCommand) if node.commands_valves() else None
    engines = participant.output(topics.ENGINE_COMMAND, idl.EngineCommand) if node.commands_engines() else None
    drive = participant.output(topics.DRIVE_COMMAND, idl.DriveCommand)
    period = participant.schedule.period_steps

    def step(ctx) -> None:
        v, e, d = node.step(ctx.t_ns, ctx.dt_ns * period, states.get(ctx), forces.get(ctx))
        if valves is not None:
            valves.write(ctx, v)
        if engines is not None:
            engines.write(ctx, e)
        drive.write(ctx, d)

    code = participant.run(step)
    log.info("controller: dropped thermo samples: %d", node.dropped)
    return code


if __name__ == "__main__":
    sys.exit(main())
