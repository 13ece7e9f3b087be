"""The Python port of the reference adhesion controller and the robot geometry it uses.
(That it equals the C++ controller is shown here period by period against the C++ model in a
closed loop with the thermo model, SameCommandsAsTheCppController, and in the whole distributed
closed loop: tests/integration/clients.)"""

import functools
import math
import os
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

from adhesion_controller import VALVE_COUNT, AdhesionController, AdhesionControllerParams, AdhesionMeasurement
from engine_controller import EngineController, EngineControllerParams
from climbsim.config import drive_command_at, load_scenario

ROOT = Path(os.environ.get("CLIMBSIM_ROOT", Path(__file__).resolve().parents[4]))
BIN = Path(os.environ.get("CLIMBSIM_BIN_DIR", ROOT / "build" / "bin"))
CRACK_DESCENT = ROOT / "deploy/scenarios/crack-descent.yaml"


@functools.cache
def crack_descent():
    return load_scenario(CRACK_DESCENT)


def cromsci_params(**changes) -> AdhesionControllerParams:
    """The params of crack-descent's robot (as the C++ controller has them), with `changes`."""
    reference = dict(crack_descent().reference, desired_downforce_n=2200.0, balance=True)
    return AdhesionControllerParams(**{**reference, **changes})


class Geometry(unittest.TestCase):
    def test_the_chambers_tile_the_sealed_disc_and_sit_where_they_are_numbered(self):
        p = crack_descent().reference
        areas, centroids = p["chamber_area_m2"], p["p_RobotChamber_m"]
        self.assertEqual(len(areas), VALVE_COUNT)
        # cromsci: sealed diameter 0.72 m.
        self.assertAlmostEqual(sum(areas), math.pi * 0.36 ** 2, places=12)
        self.assertEqual(centroids[6], (0.0, 0.0))
        x, y = centroids[0]  # chamber 1 on +x
        self.assertGreater(x, 0.15)
        self.assertAlmostEqual(y, 0.0)
        x3, y3 = centroids[2]  # counter-clockwise: chamber 3 at 120 degrees
        self.assertAlmostEqual(math.atan2(y3, x3), math.radians(120))

    def test_the_default_scenario_loads_with_its_robot_and_drive_schedule(self):
        s = crack_descent()
        self.assertEqual(s.controller_type, "reference")
        self.assertEqual(s.reference["desired_downforce_n"], 2200)
        self.assertEqual(s.engine_count, 3)
        self.assertEqual(drive_command_at(s.drive, 1_999_999_999).vx_mps, 0.0)
        self.assertEqual(drive_command_at(s.drive, 2_000_000_000).vx_mps, 0.05)


class OneValidation(unittest.TestCase):
    """The scenario and robot files have one validation, the C++ one: a value out of range is
    refused by climbsim-controller and climbsim-py-controller with the same message, exit 2."""

    def refusals(self, scenario: Path) -> tuple[subprocess.CompletedProcess, subprocess.CompletedProcess]:
        env = dict(os.environ, CLIMBSIM_BIN_DIR=str(BIN))
        cpp = subprocess.run([str(BIN / "climbsim-controller"), "--scenario", str(scenario), "--name", "controller"],
                             capture_output=True, text=True, env=env, timeout=60)
        py = subprocess.run([sys.executable, str(Path(__file__).with_name("climbsim_py_controller.py")),
                             "--scenario", str(scenario), "--name", "controller"],
                            capture_output=True, text=True, env=env, timeout=60)
        return cpp, py

    def assert_same_refusal(self, scenario: Path, key: str) -> None:
        cpp, py = self.refusals(scenario)
        self.assertEqual(cpp.returncode, 2, cpp.stderr)
        self.assertEqual(py.returncode, 2, py.stderr)
        cpp_lines = [line.split(" error: ", 1)[1] for line in cpp.stderr.splitlines() if " error: " in line]
        py_lines = [line.removeprefix("climbsim-py-controller: error: ") for line in py.stderr.splitlines()
                    if line.startswith("climbsim-py-controller: error: ")]
        self.assertEqual(len(cpp_lines), 1, cpp.stderr)
        self.assertEqual(py_lines, cpp_lines, py.stderr)
        self.assertIn(key, cpp_lines[0])

    def test_a_set_point_out_of_range_in_the_scenario(self):
        text = CRACK_DESCENT.read_text().replace("robot: cromsci",
                                                 f"robot: {ROOT / 'deploy/robots/cromsci.yaml'}")
        text = text.replace("downforce_n: 2200", "downforce_n: -5")
        with tempfile.TemporaryDirectory() as tmp:
            scenario = Path(tmp) / "bad-setpoint.yaml"
            scenario.write_text(text)
            self.assert_same_refusal(scenario, "controller.downforce_n = -5")

    def test_a_valve_stroke_out_of_range_in_the_robot(self):
        robot_text = (ROOT / "deploy/robots/cromsci.yaml").read_text()
        self.assertIn("full_stroke_s: 0.2\n", robot_text)
        bad = robot_text.replace("full_stroke_s: 0.2\n", "full_stroke_s: -0.2\n")
        with tempfile.TemporaryDirectory() as tmp:
            (Path(tmp) / "robot.yaml").write_text(bad)
            scenario = Path(tmp) / "s.yaml"
            scenario.write_text(CRACK_DESCENT.read_text().replace("robot: cromsci", "robot: robot.yaml"))
            self.assert_same_refusal(scenario, "full_stroke_s = -0.2")


class SameCommandsAsTheCppController(unittest.TestCase):
    """The port step by step against the C++ model: climbsim-adhesion-loop runs the C++ controller
    in a closed loop with the real thermo model and prints each period's measurement and commands
    as hexadecimal floats; the port, fed the same measurements, gives the same commands bit for
    bit. Three loops of 20 s (12,000 periods): several leaks flooding the reservoir together
    (step 2b gives chambers up, their valves close at the trial's rate, the demand is capped), a
    crack under one chamber (isolation, probes, trials, re-admission) and set-point changes."""

    def assert_same_commands(self, case: str, duration_s: float = 20.0) -> AdhesionController:
        done = subprocess.run([str(BIN / "climbsim-adhesion-loop"), str(ROOT / "deploy/robots/cromsci.yaml"), case,
                               str(duration_s)], capture_output=True, text=True, timeout=120, check=True)
        c = AdhesionController(cromsci_params())
        rows = done.stdout.splitlines()
        self.assertEqual(len(rows), round(duration_s / 0.005))
        for row in rows:
            cells = row.split()
            values = [float.fromhex(v) for v in cells[1:]]
            pressures, (force, pf_x, pf_y, set_point), commands = values[:8], values[8:12], values[12:]
            if set_point != c.params.desired_downforce_n:
                c.set_desired_downforce(set_point)
            openings = c.step(AdhesionMeasurement(pressure_pa=pressures, downforce_n=force, p_RobotPF_m=(pf_x, pf_y)),
                              0.005)
            self.assertEqual([u.hex() for u in openings], [u.hex() for u in commands], f"t_ns {cells[0]}")
        return c

    def test_several_leaks_flooding_the_reservoir_together(self):
        c = self.assert_same_commands("upper-strips")
        self.assertGreaterEqual(c.flood_isolation_count, 1)  # step 2b acted
        self.assertEqual([c.isolated[i] for i in (2, 3, 4)], [True, True, True])

    def test_a_crack_under_one_chamber_isolated_probed_and_readmitted(self):
        c = self.assert_same_commands("crack")
        self.assertGreaterEqual(c.isolation_count, 1)
        self.assertGreaterEqual(c.probe_count, 1)
        self.assertFalse(any(c.isolated))

    def test_set_point_changes(self):
        self.assert_same_commands("set-point")


class Loops(unittest.TestCase):
    def measurement(self, downforce_n, chamber_pa=95000.0, reservoir_pa=83000.0, pf=(0.0, 0.0), chambers=None):
        pressures = list(chambers) if chambers else [chamber_pa] * VALVE_COUNT
        return AdhesionMeasurement(pressure_pa=pressures + [reservoir_pa], downforce_n=downforce_n, p_RobotPF_m=pf)

    def test_too_little_downforce_opens_every_valve_and_raises_the_suction_target(self):
        c = AdhesionController(cromsci_params())
        s0 = c.s_base_pa
        for _ in range(100):
            openings = c.step(self.measurement(500.0), 0.005)
        self.assertGreater(c.s_base_pa, s0)
        self.assertTrue(all(0.0 < u <= 1.0 for u in openings), openings)

    def test_a_point_of_action_towards_chamber_1_makes_chamber_1_pull_less_than_chamber_4(self):
        c = AdhesionController(cromsci_params())
        for _ in range(100):
            openings = c.step(self.measurement(2200.0, pf=(0.05, 0.0)), 0.005)
        self.assertGreater(c.trim[0], 0.0)
        self.assertLess(c.trim[3], 0.0)
        self.assertLess(openings[0], openings[3])
        self.assertEqual(c.trim[6], 0.0)  # the centre chamber has no side

    def test_a_chamber_at_ambient_with_its_valve_open_is_isolated_and_readmitted_once_sealed(self):
        c = AdhesionController(cromsci_params())
        leaking = [100000.0] + [95000.0] * (VALVE_COUNT - 1)
        for _ in range(200):  # 1 s: the valve opens, the chamber stays at ambient: a leak
            openings = c.step(self.measurement(1900.0, chambers=leaking), 0.005)
        self.assertTrue(c.isolated[0])
        self.assertEqual(openings[0], 0.0)
        self.assertFalse(any(c.isolated[1:]))
        self.assertEqual(c.isolation_count, 1)
        sealed = [96500.0] + [95000.0] * (VALVE_COUNT - 1)  # holds suction with its valve closed
        for _ in range(100):
            c.step(self.measurement(2150.0, chambers=sealed), 0.005)
        self.assertFalse(c.isolated[0])

    def test_a_chamber_short_of_its_share_with_its_valve_fully_open_is_isolated(self):
        c = AdhesionController(cromsci_params())
        share = 2200.0 / c.total_area_m2
        # Chamber 1 stays 17 % short of its share (lambda below isolate_leak_ratio: no crack) on a
        # reservoir that is not the limit: its valve opens fully, and 1 s later it is given up.
        chambers = [100000.0 - 0.83 * share] + [100000.0 - share] * (VALVE_COUNT - 1)
        fully_open_at = None
        for k in range(3000):
            openings = c.step(self.measurement(2200.0, chambers=chambers, reservoir_pa=92000.0), 0.005)
            if fully_open_at is None and c.expected_opening[0] >= 1.0:
                fully_open_at = k
            if c.isolated[0]:
                break
        self.assertIsNotNone(fully_open_at)
        self.assertTrue(c.isolated[0])
        self.assertEqual(openings[0], 0.0)
        self.assertAlmostEqual((k - fully_open_at) * 0.005, c.params.isolate_saturated_s, delta=0.011)
        self.assertFalse(any(c.isolated[1:]))

    def test_the_force_demand_does_not_wind_up_while_the_reservoir_caps_every_chamber(self):
        c = AdhesionController(cromsci_params())
        # The reservoir holds 3 kPa (engines spinning up): every target is capped at 2.7 kPa.
        for _ in range(400):
            c.step(self.measurement(700.0, chamber_pa=97300.0, reservoir_pa=97000.0), 0.005)
        self.assertLessEqual(c.force_demand_n, c.params.desired_downforce_n)

    def test_a_non_finite_measurement_is_refused_and_changes_nothing(self):
        c = AdhesionController(cromsci_params())
        c.step(self.measurement(1000.0), 0.005)
        before = (c.s_base_pa, list(c.trim), list(c.opening))
        with self.assertRaises(ValueError):
            c.step(self.measurement(float("nan")), 0.005)
        self.assertEqual(before, (c.s_base_pa, list(c.trim), list(c.opening)))

    def test_bad_parameters_are_refused_naming_them(self):
        with self.assertRaisesRegex(ValueError, "max_trim"):
            AdhesionController(cromsci_params(max_trim=1.0))
        with self.assertRaisesRegex(ValueError, "probe_rise_ratio"):
            AdhesionController(cromsci_params(probe_rise_ratio=0.0))
        with self.assertRaisesRegex(ValueError, "readmit_max_opening"):
            AdhesionController(cromsci_params(readmit_max_opening=1.0))
        with self.assertRaisesRegex(ValueError, "valve_command_delay_s"):
            AdhesionController(cromsci_params(valve_command_delay_s=-0.01))
        with self.assertRaisesRegex(ValueError, "flood_demand_max_ratio"):
            AdhesionController(cromsci_params(flood_demand_max_ratio=0.5))
        with self.assertRaisesRegex(ValueError, "fan_max_suction_pa"):
            AdhesionController(cromsci_params(fan_max_suction_pa=0.0))


def grid_without_reservoir(folder: Path) -> Path:
    """A scenario of the 2 x 2 grid without its reservoir, one engine on each cell (the robot file
    beside it): several chambers, each pumped by its own engine."""
    lines, skip = [], False
    for line in (ROOT / "deploy/robots/grid-2x2.yaml").read_text().splitlines():
        if line.startswith(("reservoir:", "valves:", "engines:")):
            skip = True
            continue
        if skip and (not line or line.startswith(" ")):
            continue
        skip = False
        lines.append(line)
    lines += ["engines:", "  count: 4", "  dp_max_pa: 22000", "  flow_max_m3ps: 0.030", "  speed_lag_s: 0.5",
              "  chambers: [1, 2, 3, 4]"]
    robot = folder / "grid-engines.yaml"
    robot.write_text("\n".join(lines) + "\n")
    scenario = folder / "hold-grid-engines.yaml"
    scenario.write_text((ROOT / "deploy/scenarios/hold-single-chamber.yaml").read_text()
                        .replace("robot: single-chamber", f"robot: {robot}").replace("name: hold-single-chamber",
                                                                                    "name: hold-grid-engines"))
    return scenario


class SameSpeedsAsTheCppEngineLaw(unittest.TestCase):
    """The engine law's port step by step against the C++ law: climbsim-engine-loop runs it in a
    closed loop with the real thermo model (a strip of chamber 1 leaking 6 times as much from 2 s
    to 5 s) and prints each period's measurement and speeds as hexadecimal floats; the port, fed
    the same measurements, gives the same speeds bit for bit."""

    def assert_same_speeds(self, scenario: Path, robot: Path, setpoint_n: float) -> EngineController:
        params = dict(load_scenario(scenario).engine_reference, desired_downforce_n=setpoint_n)
        done = subprocess.run([str(BIN / "climbsim-engine-loop"), str(robot), repr(setpoint_n), "8"],
                              capture_output=True, text=True, timeout=120, check=True)
        law = EngineController(EngineControllerParams(**params))
        n, engines = len(params["chamber_area_m2"]), len(params["engine_chamber"])
        rows = done.stdout.splitlines()
        self.assertEqual(len(rows), 1600)
        for row in rows:
            cells = row.split()
            values = [float.fromhex(v) for v in cells[1:]]
            self.assertEqual(len(values), n + 3 + engines)
            pressures, (force, pf_x, pf_y), speeds = values[:n], values[n:n + 3], values[n + 3:]
            got = law.step(AdhesionMeasurement(pressure_pa=pressures, downforce_n=force, p_RobotPF_m=(pf_x, pf_y)),
                           0.005)
            self.assertEqual([w.hex() for w in got], [w.hex() for w in speeds], f"t_ns {cells[0]}")
        return law

    def test_the_single_chamber_robot(self):
        law = self.assert_same_speeds(ROOT / "deploy/scenarios/hold-single-chamber.yaml",
                                      ROOT / "deploy/robots/single-chamber.yaml", 700.0)
        self.assertLess(law.speed[0], 1.0)

    def test_four_chambers_on_four_engines_with_balance_trims(self):
        with tempfile.TemporaryDirectory() as folder:
            scenario = grid_without_reservoir(Path(folder))
            law = self.assert_same_speeds(scenario, scenario.with_name("grid-engines.yaml"), 1500.0)
        self.assertTrue(any(b != 0.0 for b in law.trim), law.trim)  # the trims moved


class EngineLawPort(unittest.TestCase):
    """The engine law's port (engine_controller.py) on the single-chamber robot, configured as the
    C++ controller configures it. (Its numbers equal the C++ law's: the distributed runs of
    tests/integration/clients compare the whole traces.)"""

    @functools.cache
    def scenario(self):
        return load_scenario(ROOT / "deploy/scenarios/hold-single-chamber.yaml")

    def law(self, **changes) -> EngineController:
        return EngineController(EngineControllerParams(**{**self.scenario().engine_reference, **changes}))

    def test_the_single_chamber_scenario_gives_the_law_its_robot(self):
        s = self.scenario()
        self.assertEqual(s.controller_type, "reference")
        self.assertFalse(s.has_reservoir)
        self.assertEqual(s.chamber_count, 1)
        e = s.engine_reference
        self.assertEqual(e["engine_chamber"], [0])
        self.assertEqual(e["desired_downforce_n"], 700.0)
        self.assertEqual(e["max_suction_pa"], 15000.0)  # engines.dp_max_pa
        self.assertEqual(e["engine_integral_s"], 0.3)   # engines.speed_lag_s
        self.assertAlmostEqual(e["chamber_area_m2"][0], math.pi * 0.25 ** 2, places=3)

    def test_the_first_speed_is_the_feed_forward_and_the_proportional_kick(self):
        law = self.law()
        p = law.params
        target = p.desired_downforce_n / p.chamber_area_m2[0]
        speed = law.step(AdhesionMeasurement(pressure_pa=[p.ambient_pressure_pa]), 0.005)[0]
        error = target / p.max_suction_pa
        self.assertAlmostEqual(speed, math.sqrt(error) + error + 0.005 * error / p.engine_integral_s, places=12)

    def test_speeds_stay_within_0_and_1_and_move_with_the_error(self):
        law = self.law()
        ambient = law.params.ambient_pressure_pa
        for _ in range(2000):  # no suction at all: the speed climbs to full and stays there
            speed = law.step(AdhesionMeasurement(pressure_pa=[ambient]), 0.005)[0]
        self.assertEqual(speed, 1.0)
        for _ in range(2000):  # far deeper than the target: down to rest, never below
            speed = law.step(AdhesionMeasurement(pressure_pa=[ambient - 14000.0]), 0.005)[0]
        self.assertEqual(speed, 0.0)

    def test_bad_parameters_and_measurements_are_refused_naming_them(self):
        with self.assertRaisesRegex(ValueError, "engine 1 pumps chamber 2"):
            self.law(engine_chamber=[1])
        with self.assertRaisesRegex(ValueError, "engine_integral_s"):
            self.law(engine_integral_s=0.0)
        with self.assertRaisesRegex(ValueError, "2 pressures for 1 chambers"):
            self.law().step(AdhesionMeasurement(pressure_pa=[1e5, 1e5]), 0.005)


if __name__ == "__main__":
    unittest.main()
