"""The C client example (climbsim-c-valves, Cyclone DDS's C API) in the whole closed loop
through the launcher: with the scenario's controller type external, the valves (on a robot
without a reservoir: the engines) are the C client's alone, and it holds the robot on the wall
down the crack, on the 2 x 2 grid, and on the single-chamber robot by the engine law."""

from __future__ import annotations

import json
import math
import subprocess
import sys
import unittest
from pathlib import Path

from common import DomainLease, compose_copy, compose_run, finite, mean_after, trace_column

EXTERNAL = "controller={type: external}"

#: An outsider's process on the run's domain: writes thermo/ChamberState samples that claim to
#: come from "thermo" (all chambers at ambient: a controller that took them would open every
#: valve), 60 every 2 ms, stamped with steps around the run's.
FORGER = """
import sys, time
import climbsim_idl as idl
from climbsim import qos, topics
from climbsim.dds import DdsContext
dds = DdsContext(int(sys.argv[1]))
writer = dds.writer(topics.CHAMBER_STATE, idl.ChamberState, qos.STEP_DATA)
print("forging", flush=True)
step = 0
while True:
    for k in range(60):
        writer.write(idl.ChamberState(source="thermo", step=step + k % 8, t_ns=0, pressure_pa=[101325.0] * 8,
                                      valve_opening=[0.0] * 7, engine_speed=[], segment_mass_flow_kgps=[]))
    step += 1
    time.sleep(0.002)
"""


class CClientInTheClosedLoop(unittest.TestCase):
    def test_the_c_client_commands_the_valves_and_holds_the_robot_on_crack_descent(self):
        compose = compose_copy("compose.c-controller.yaml", "c-client")
        code, run_dir, log = compose_run("c-client-crack-descent", ["crack-descent", "-f", str(compose), "--set", EXTERNAL])
        self.assertEqual(code, 0, log[-3000:])
        self.assertIn("valves: ready", log)
        summary = json.loads((run_dir / "summary.json").read_text())
        self.assertTrue(summary["completed"])
        self.assertFalse(summary["fell"])
        trace = run_dir / "trace.csv"
        force = trace_column(trace, "downforce_n")
        self.assertEqual(len(force), 4000)
        openings = [max(finite(trace_column(trace, f"valve{i}"))) for i in range(1, 8)]
        self.assertTrue(all(o > 0.2 for o in openings), openings)
        # After the 2 s of holding while the vacuum builds: the robot is held near its F* =
        # 2000 N (compose.c-controller.yaml; the robot file says 2200 N).
        held = finite(force[400:2000])
        mean = sum(held) / len(held)
        print(f"bench: c-client: mean_downforce_2_10s_n={mean:.0f} min_downforce_after_2s_n={min(held):.0f}")
        self.assertGreater(mean, 0.75 * 2000)
        self.assertLess(mean, 1.25 * 2000)
        # The client publishes its set-point with the valves: the trace, the summary and the plot
        # have its 2000 N, not the robot file's 2200 N.
        self.assertEqual(set(trace_column(trace, "downforce_setpoint_n")[2:]), {2000.0})
        self.assertEqual(summary["downforce_setpoint_n"], 2000.0)

    def test_an_outsiders_forged_chamber_states_change_nothing_in_the_c_clients_run(self):
        # The security tests against the C client: an outsider floods its ChamberState input with
        # samples that claim to be thermo's. In the reader's shared KEEP_LAST history they would
        # push thermo's own samples out before the client read them; taken per writer as they
        # arrive, they are dropped (not thermo's DDS participant) and the trace is the
        # undisturbed run's, bit for bit.
        compose = compose_copy("compose.c-controller.yaml", "c-client-forged")
        args = ["crack-descent", "-f", str(compose), "--set", EXTERNAL, "--set", "duration_s=4"]
        code, quiet_dir, log = compose_run("c-client-quiet", args)
        self.assertEqual(code, 0, log[-3000:])
        lease = DomainLease()
        outsider = subprocess.Popen([sys.executable, "-c", FORGER, str(lease.id)], stdout=subprocess.PIPE,
                                    stderr=subprocess.STDOUT, text=True)
        try:
            self.assertEqual(outsider.stdout.readline().strip(), "forging", "the outsider did not start")
            lease.release()  # the launcher takes the domain's lock itself
            code, forged_dir, log = compose_run("c-client-forged", args + ["--domain", str(lease.id)])
        finally:
            outsider.kill()
            outsider.wait()
        self.assertEqual(code, 0, log[-3000:])
        self.assertIn("dropped a sample of 'thermo/ChamberState'", log, "the forged samples never arrived")
        self.assertEqual((forged_dir / "trace.csv").read_bytes(), (quiet_dir / "trace.csv").read_bytes())

    def test_without_the_c_client_an_external_scenario_is_refused_before_step_0(self):
        # The control experiment: with no valve writer on the roster, thermo's ValveCommand input
        # has no producer, and the clock refuses the run (an observer's commands would never be
        # read: a stamped input waits only for producers on the roster).
        compose = compose_copy("compose.yaml", "c-client-absent")
        code, _, log = compose_run("c-client-absent", ["crack-descent", "-f", str(compose), "--set", EXTERNAL,
                                                       "--set", "duration_s=2"])
        self.assertEqual(code, 2, log[-3000:])
        self.assertIn("reads topic 'controller/ValveCommand' that no participant on the roster writes", log)


class CClientOnOtherRobots(unittest.TestCase):
    CLIENT = '[climbsim-c-valves, --downforce-n, "2000"]'

    def run_c(self, scenario: str, tag: str, client: str, *more: str) -> tuple[int, Path, str]:
        compose = compose_copy("compose.c-controller.yaml", tag, {self.CLIENT: client})
        return compose_run(tag, [scenario, "-f", str(compose), "--set", EXTERNAL, "--set", "duration_s=6", *more])

    def test_the_c_client_holds_the_single_chamber_robot_by_its_engine_as_the_cpp_controller_does(self):
        code, run_dir, log = self.run_c("hold-single-chamber", "c-client-single-chamber",
                                        '[climbsim-c-valves, --downforce-n, "700", --engines]')
        self.assertEqual(code, 0, log[-3000:])
        self.assertIn("C engine controller", log)
        summary = json.loads((run_dir / "summary.json").read_text())
        self.assertTrue(summary["completed"])
        self.assertFalse(summary["fell"])
        self.assertEqual(summary["downforce_setpoint_n"], 700.0)
        trace = run_dir / "trace.csv"
        force = trace_column(trace, "downforce_n")
        self.assertEqual(len(force), 1200)
        held = mean_after(force, 800)  # 4-6 s
        print(f"bench: c-client: hold-single-chamber: mean_downforce_4_6s_n={held:.2f} (F* 700)")
        self.assertAlmostEqual(held, 700.0, delta=7.0)
        # The engine law in C is the C++ controller's operation by operation: the reference
        # controller's run of the same scenario gives the same trace, byte for byte.
        cpp_code, cpp_dir, cpp_log = compose_run("cpp-controller-single-chamber-for-c",
                                                 ["hold-single-chamber", "-f",
                                                  str(compose_copy("compose.yaml", "cpp-controller-single-chamber-for-c")),
                                                  "--set", "duration_s=6"])
        self.assertEqual(cpp_code, 0, cpp_log[-3000:])
        self.assertEqual(trace.read_bytes(), (cpp_dir / "trace.csv").read_bytes())

    def test_the_c_client_holds_the_grid_robot_by_its_four_valves(self):
        code, run_dir, log = self.run_c("hold-grid-2x2", "c-client-grid", '[climbsim-c-valves, --downforce-n, "1500"]')
        self.assertEqual(code, 0, log[-3000:])
        summary = json.loads((run_dir / "summary.json").read_text())
        self.assertTrue(summary["completed"])
        self.assertFalse(summary["fell"])
        trace = run_dir / "trace.csv"
        openings = [max(finite(trace_column(trace, f"valve{i}"))) for i in range(1, 5)]
        self.assertTrue(all(o > 0.0 for o in openings), openings)
        held = mean_after(trace_column(trace, "downforce_n"), 800)
        print(f"bench: c-client: hold-grid-2x2: mean_downforce_4_6s_n={held:.2f} (F* 1500)")
        self.assertAlmostEqual(held, 1500.0, delta=0.02 * 1500.0)

    def test_without_engines_on_a_robot_without_a_reservoir_nobody_commands_its_engine_and_the_run_is_refused(self):
        # External leaves the single chamber's engine to the client; the client started for valves
        # writes none, so thermo's EngineCommand has no producer and the clock refuses before step 0.
        code, _, log = self.run_c("hold-single-chamber", "c-client-single-no-engines", self.CLIENT)
        self.assertEqual(code, 2, log[-3000:])
        self.assertIn("reads topic 'controller/EngineCommand' that no participant on the roster writes", log)


if __name__ == "__main__":
    unittest.main()
