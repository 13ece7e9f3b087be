"""The Python runtime (common/python/climbsim, Cyclone DDS) against the real C++ services on
Fast DDS: a Python participant gates the real clock, fails a run by name, an observer
listens without gating, and the Python reference controller in the whole closed loop gives
the C++ controller's downforce trace on crack-descent (within 2 %)."""

from __future__ import annotations

import math
import subprocess
import sys
import threading
import time
import unittest
from pathlib import Path

import climbsim_idl as idl
from climbsim import topics
from climbsim.dds import DdsContext, wait_for
from climbsim.lockstep import EXIT_FAILED, EXIT_OK, LockstepParticipant, Observer, Schedule

from common import BIN, ROOT, RUNS, DomainLease, compose_copy, compose_run, finite, mean_after, start, trace_column


#: An outsider's process: floods test/cpp with samples that claim to come from "cpp", in bursts
#: of 60 (more than one history holds) every 10 ms: the Python participant must drain and drop
#: each forged sample, and a flood without pauses takes its CPU on a busy machine.
FORGED_VALUE = 0xF0F0F0F0
FORGER = f"""
import sys, time
import climbsim_idl as idl
from climbsim import qos
from climbsim.dds import DdsContext, wait_for
dds = DdsContext(int(sys.argv[1]))
writer = dds.writer("test/cpp", idl.TestSample, qos.STEP_DATA)
print("forging", flush=True)
step = 0
while True:
    for k in range(60):
        writer.write(idl.TestSample(source="cpp", step=step + k % 8, t_ns=0, value={FORGED_VALUE}, payload=[]))
    step += 1
    time.sleep(0.010)
"""


class PythonParticipantWithTheRealClock(unittest.TestCase):
    def setUp(self):
        self.lease = DomainLease()
        self.dir = RUNS / f"python-client-{self.id().split('.')[-1]}"
        self.procs = []

    def tearDown(self):
        for p in self.procs:
            if p.poll() is None:
                p.kill()
                p.wait()
        self.lease.release()

    def start_clock(self, roster: str, steps: int) -> None:
        self.procs.append(start([BIN / "climbsim-clock", "--roster", roster, "--steps", steps, "--step-ms", 5,
                                 "--start-timeout-s", 60, "--step-timeout-s", 30, "--domain", self.lease.id],
                                self.dir / "clock.log"))

    def clock_exit(self) -> int:
        return self.procs[0].wait(timeout=60)

    def test_a_python_roster_member_exchanges_stamped_data_with_a_cpp_participant(self):
        # climbsim-test-participant "cpp" writes test/cpp every step and reads test/py; "py"
        # (period 2, offset 1) reads test/cpp and writes test/py: both directions of stamped data.
        self.start_clock("cpp,py", 40)
        record = self.dir / "cpp-read.txt"
        self.procs.append(start([BIN / "climbsim-test-participant", "--name", "cpp", "--reads", "py",
                                 "--record", record, "--domain", self.lease.id], self.dir / "cpp.log"))
        observer = Observer(self.lease.id)  # listens on the same domain, gates nothing
        p = LockstepParticipant("py", self.lease.id, Schedule(2, 1))
        cpp_in = p.input("test/cpp", idl.TestSample)
        py_out = p.output("test/py", idl.TestSample)
        written = {}

        def step(ctx):
            samples = cpp_in.get(ctx)
            self.assertEqual([s.source for s in samples], ["cpp"])
            self.assertEqual(samples[0].step, ctx.step - 1)  # cpp is due every step
            written[ctx.step] = (samples[0].value + ctx.step) % 2**64
            py_out.write(ctx, idl.TestSample(value=written[ctx.step]))

        self.assertEqual(p.run(step), EXIT_OK)
        self.assertEqual(self.clock_exit(), 0, (self.dir / "clock.log").read_text())
        self.assertEqual(self.procs[1].wait(timeout=30), 0, (self.dir / "cpp.log").read_text())
        self.assertEqual(sorted(written), list(range(1, 40, 2)))
        # cpp read, at each step k >= 2, what py wrote at its last due step before k.
        lines = [line.split() for line in record.read_text().splitlines()]
        self.assertEqual(len(lines), 38)
        for step, source, stamp, value in lines:
            self.assertEqual(source, "py")
            self.assertEqual(int(stamp), int(step) - 1 if int(step) % 2 == 0 else int(step) - 2)
            self.assertEqual(int(value), written[int(stamp)])
        observer.poll()
        self.assertIsNotNone(observer.run_start)
        self.assertEqual(sorted(e.participant for e in observer.run_start.roster), ["cpp", "py"])
        self.assertEqual(observer.stop.kind, idl.StopKind.STOP_COMPLETED)
        self.assertEqual(observer.stop.last_step, 39)

    def test_an_outsiders_flood_of_forged_samples_does_not_push_out_the_producers_own(self):
        # An outsider (its own process and DDS participant) writes test/cpp samples that claim
        # to come from "cpp", 60 every 10 ms, stamped with the steps the Python participant is
        # about to read. In one shared KEEP_LAST 34 history per key they would push cpp's own
        # samples out before they were read. Each writer has its own queue: py reads
        # cpp's samples at every due step, and the forged ones are dropped and counted. The
        # outsider's writer matches py's input before cpp's does: py must arm only once cpp's
        # own writer has matched, or cpp's first sample never reaches it and the run stalls.
        self.start_clock("cpp,py", 200)
        self.procs.append(start([BIN / "climbsim-test-participant", "--name", "cpp", "--reads", "py",
                                 "--domain", self.lease.id], self.dir / "cpp.log"))
        outsider = subprocess.Popen([sys.executable, "-c", FORGER, str(self.lease.id)], stdout=subprocess.PIPE,
                                    stderr=subprocess.STDOUT, text=True)
        self.procs.append(outsider)
        self.assertEqual(outsider.stdout.readline().strip(), "forging", "the outsider did not start")
        p = LockstepParticipant("py", self.lease.id, Schedule(2, 1))
        cpp_in = p.input("test/cpp", idl.TestSample)
        py_out = p.output("test/py", idl.TestSample)
        # py arms once cpp's own writer has matched, whatever else has: the outsider's writer
        # must have matched too before the run, or the 0.2 s run may end before its flood
        # reaches py and the test tests nothing.
        wait_for(lambda: cpp_in.matched_writers() >= 2, p.dds.notifier, 30, "cpp's and the outsider's writers")
        read = []

        def step(ctx):
            samples = cpp_in.get(ctx)
            self.assertEqual([(s.source, s.step) for s in samples], [("cpp", ctx.step - 1)])
            self.assertNotEqual(samples[0].value, FORGED_VALUE, "a forged sample was taken as cpp's")
            read.append(ctx.step)
            py_out.write(ctx, idl.TestSample(value=samples[0].value))

        self.assertEqual(p.run(step), EXIT_OK)
        self.assertEqual(self.clock_exit(), 0, (self.dir / "clock.log").read_text())
        self.assertEqual(read, list(range(1, 200, 2)))
        self.assertGreater(p.dropped.dropped, 0, "the outsider's samples never arrived: the test tests nothing")

    def test_a_python_step_that_raises_fails_the_run_naming_it_and_an_observer_sees_the_stop(self):
        self.start_clock("py", 1000)
        observer = Observer(self.lease.id)
        p = LockstepParticipant("py", self.lease.id)

        def step(ctx):
            if ctx.step == 7:
                raise RuntimeError("pressure sensor unplugged")

        self.assertEqual(p.run(step), EXIT_FAILED)
        self.assertNotEqual(self.clock_exit(), 0)
        for _ in range(50):
            if observer.stop is not None:
                break
            observer.wait(0.2)
        self.assertIsNotNone(observer.stop, "the observer never saw the latched Stop")
        self.assertEqual(observer.stop.kind, idl.StopKind.STOP_FAILED)
        self.assertEqual(observer.stop.culprit, "py")
        self.assertIn("failed at step 7: pressure sensor unplugged", observer.stop.reason)
        self.assertNotIn("step 7: step 7", observer.stop.reason)  # the step once, the clock's
        # A failure stops at once: last_step is the end of the horizon granted so far (at most
        # a window, 16 steps by default, past the step that failed).
        self.assertGreaterEqual(observer.stop.last_step, 7)
        self.assertLess(observer.stop.last_step, 7 + 16)


class PythonControllerInTheClosedLoop(unittest.TestCase):
    def test_crack_descent_downforce_within_2_percent_of_the_cpp_controller(self):
        py_compose = compose_copy("compose.python-controller.yaml", "python-controller")
        py_code, py_dir, py_log = compose_run("python-controller-crack-descent", ["crack-descent", "-f", str(py_compose)])
        self.assertEqual(py_code, 0, py_log[-3000:])
        cpp_compose = compose_copy("compose.yaml", "cpp-controller")
        cpp_code, cpp_dir, cpp_log = compose_run("cpp-controller-crack-descent", ["crack-descent", "-f", str(cpp_compose)])
        self.assertEqual(cpp_code, 0, cpp_log[-3000:])
        py = trace_column(py_dir / "trace.csv", "downforce_n")
        cpp = trace_column(cpp_dir / "trace.csv", "downforce_n")
        self.assertEqual(len(py), len(cpp))
        self.assertEqual(len(py), 4000)  # 20 s at 5 ms
        worst = 0.0
        for k, (a, b) in enumerate(zip(py, cpp)):
            self.assertEqual(math.isfinite(a), math.isfinite(b), f"row {k}")
            if math.isfinite(b) and abs(b) > 1.0:
                worst = max(worst, abs(a - b) / abs(b))
        print(f"bench: python-controller: max_rel_downforce_diff={worst:.3g} rows={len(py)}", file=sys.stderr)
        self.assertLessEqual(worst, 0.02)
        # The port follows the C++ controller operation by operation: the whole trace is the same
        # bytes (docs/controllers.md#the-reference-controller).
        self.assertEqual((py_dir / "trace.csv").read_bytes(), (cpp_dir / "trace.csv").read_bytes())
        # Each controller publishes its set-point with its valve commands; thermo holds it and the
        # trace shows it: from row 2 on (the first command reaches thermo at step 1) 2200 N.
        py_setpoint = trace_column(py_dir / "trace.csv", "downforce_setpoint_n")
        self.assertEqual(py_setpoint, trace_column(cpp_dir / "trace.csv", "downforce_setpoint_n"))
        self.assertEqual(py_setpoint[0], 0.0)
        self.assertEqual(set(py_setpoint[2:]), {2200.0})
        # The loop did its job: held near the 2200 N set-point after the vacuum built up.
        held = finite(cpp[len(cpp) // 2:])
        self.assertGreater(min(finite(py[len(py) // 2:])), 0.3 * 2200)
        self.assertAlmostEqual(sum(held) / len(held), sum(finite(py[len(py) // 2:])) / len(held), delta=0.02 * 2200)


    def test_crack_upper_strips_the_same_trace_as_the_cpp_controller(self):
        # Several leaks flooding the reservoir together: the controller's step 2b gives chambers
        # 3 and 5 up (docs/controllers.md#the-reference-controller); the port does the
        # same at the same step, so the whole trace is the same bytes.
        py_compose = compose_copy("compose.python-controller.yaml", "python-controller-cus")
        py_code, py_dir, py_log = compose_run("python-controller-crack-upper-strips",
                                              ["crack-upper-strips", "-f", str(py_compose)])
        self.assertEqual(py_code, 0, py_log[-3000:])
        cpp_compose = compose_copy("compose.yaml", "cpp-controller-cus")
        cpp_code, cpp_dir, cpp_log = compose_run("cpp-controller-crack-upper-strips",
                                                 ["crack-upper-strips", "-f", str(cpp_compose)])
        self.assertEqual(cpp_code, 0, cpp_log[-3000:])
        self.assertEqual(len(trace_column(cpp_dir / "trace.csv", "downforce_n")), 4800)  # 24 s at 5 ms
        self.assertEqual((py_dir / "trace.csv").read_bytes(), (cpp_dir / "trace.csv").read_bytes())


class PythonControllerOnOtherRobots(unittest.TestCase):
    """climbsim-py-controller in place of climbsim-controller on the robots besides CROMSCI: the
    single-chamber robot (no reservoir: the engine law) and the 2 x 2 grid (a reservoir and four
    valves). The port follows the C++ controller operation by operation, so the whole trace is
    the same bytes, and the loop holds the downforce at the scenario's set-point."""

    def same_trace_as_cpp(self, scenario: str, setpoint_n: float) -> list[float]:
        args = [scenario, "--set", "duration_s=6"]
        py_code, py_dir, py_log = compose_run(f"python-controller-{scenario}",
                                              [*args, "-f", str(compose_copy("compose.python-controller.yaml",
                                                                             f"python-controller-{scenario}"))])
        self.assertEqual(py_code, 0, py_log[-3000:])
        cpp_code, cpp_dir, cpp_log = compose_run(f"cpp-controller-{scenario}",
                                                 [*args, "-f", str(compose_copy("compose.yaml", f"cpp-controller-{scenario}"))])
        self.assertEqual(cpp_code, 0, cpp_log[-3000:])
        trace = py_dir / "trace.csv"
        force = trace_column(trace, "downforce_n")
        self.assertEqual(len(force), 1200)  # 6 s at 5 ms
        self.assertEqual(trace.read_bytes(), (cpp_dir / "trace.csv").read_bytes())
        self.assertEqual(set(trace_column(trace, "downforce_setpoint_n")[2:]), {setpoint_n})
        held = mean_after(force, 800)  # 4-6 s
        print(f"bench: python-controller: {scenario}: mean_downforce_4_6s_n={held:.2f} (F* {setpoint_n:.0f})",
              file=sys.stderr)
        self.assertAlmostEqual(held, setpoint_n, delta=0.01 * setpoint_n)
        return force

    def test_hold_single_chamber_by_the_engine_law_the_same_trace_as_the_cpp_controller(self):
        self.same_trace_as_cpp("hold-single-chamber", 700.0)

    def test_hold_grid_2x2_by_its_four_valves_the_same_trace_as_the_cpp_controller(self):
        self.same_trace_as_cpp("hold-grid-2x2", 1500.0)


class ReadmePythonExample(unittest.TestCase):
    """The README's "A controller in Python" runs verbatim under the launcher."""

    EXAMPLE = ROOT / "services" / "controller" / "examples" / "python" / "my_controller.py"

    def readme_example(self) -> str:
        text = (ROOT / "README.md").read_text()
        start = text.index("### A controller in Python")
        section = text[start:]
        block = section[section.index("\n\n    ") + 2:]
        lines = []
        for line in block.splitlines():
            if line and not line.startswith("    "):
                break
            lines.append(line[4:])
        return "\n".join(lines).strip() + "\n"

    def test_the_readme_example_is_the_shipped_file(self):
        self.assertEqual(self.readme_example(), self.EXAMPLE.read_text())

    def test_the_readme_example_commands_the_valves_under_the_launcher(self):
        compose = compose_copy("compose.python-example.yaml", "python-example")
        code, run_dir, log = compose_run("python-example", ["crack-descent", "-f", str(compose), "--set",
                                                            "controller={type: external}", "--set", "duration_s=2"])
        self.assertEqual(code, 0, log[-3000:])
        trace = run_dir / "trace.csv"
        openings = set(finite(trace_column(trace, "valve1")))
        self.assertTrue(openings <= {0.0, 0.5} or max(openings) <= 0.5, sorted(openings)[:10])
        self.assertGreater(max(openings), 0.0)
        # Its SETPOINT_N reaches the trace (and the plot), not the robot file's set-point.
        self.assertEqual(set(trace_column(trace, "downforce_setpoint_n")[2:]), {2200.0})

    def test_the_plain_cyclonedds_observer_follows_a_run_on_the_domain_ps_shows(self):
        compose = [BIN / "climbsim-compose", "--root", ROOT, "--build", BIN.parent]
        name = "plain-observer"
        up = subprocess.run([*map(str, compose), "up", "-d", "--name", name, "--rtf", "1", "--set", "duration_s=12"],
                            capture_output=True, text=True, timeout=120)
        self.assertEqual(up.returncode, 0, up.stderr[-3000:])
        try:
            ps = subprocess.run([*map(str, compose), "ps"], capture_output=True, text=True, timeout=60).stdout
            row = next(line for line in ps.splitlines() if line.startswith(name + " "))
            domain = row.split()[2]  # RUN STATE DOMAIN ...
            # Once the run has started (its first trace rows), a listener has something to hear.
            trace = BIN.parent / "run" / name / "out" / "trace.csv"
            deadline = time.monotonic() + 90
            while time.monotonic() < deadline and not (trace.exists() and trace.read_text().count("\n") > 2):
                time.sleep(0.2)
            observer = subprocess.run([str(BIN / "climbsim-python"), str(ROOT / "services/controller/examples/python/plain_observer.py"),
                                       domain, "6"], capture_output=True, text=True, timeout=60)
            self.assertEqual(observer.returncode, 0, observer.stderr[-3000:])
            forces = [line for line in observer.stdout.splitlines() if " F = " in line]
            self.assertGreaterEqual(len(forces), 2, observer.stdout + observer.stderr)
            self.assertNotIn("deserialization failed", observer.stdout + observer.stderr)
        finally:
            subprocess.run([*map(str, compose), "down", name], capture_output=True, timeout=60)


if __name__ == "__main__":
    unittest.main()
