"""The C client example (climbsim-c-valves, Cyclone DDS's C API) in the whole closed loop
through the launcher: with the scenario's controller type external, the valves are the C
client's alone, and it holds the robot on the wall down the crack."""

from __future__ import annotations

import json
import math
import unittest

from common import compose_copy, compose_run, finite, trace_column

EXTERNAL = "controller={type: external}"


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

    def test_without_the_c_client_an_external_scenario_is_refused_before_step_0(self):
        # The control experiment: with no valve writer on the roster, thermo's ValveCommand input
        # has no producer, and the clock refuses the run (an observer's commands would never be
        # read: a stamped input waits only for producers on the roster).
        compose = compose_copy("compose.yaml", "c-client-absent")
        code, _, log = compose_run("c-client-absent", ["crack-descent", "-f", str(compose), "--set", EXTERNAL,
                                                       "--set", "duration_s=2"])
        self.assertEqual(code, 2, log[-3000:])
        self.assertIn("reads topic 'controller/ValveCommand' that no participant on the roster writes", log)


if __name__ == "__main__":
    unittest.main()
