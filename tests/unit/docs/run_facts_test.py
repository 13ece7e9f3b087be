"""docs/tools/run_facts.py on small made-up run directories (no build, no run): the facts it
writes are the trace's and the summary's, a block it does not know or a block without its end
fails, a committed block that differs from the runs is found, and README.md stays a guide
(at most 350 lines) whose Python example and docs/controllers.md's are the shipped file.

    python3 run_facts_test.py ROOT
"""

from __future__ import annotations

import csv
import importlib.util
import io
import json
import math
import re
import shutil
import sys
import tempfile
import unittest
from contextlib import redirect_stdout
from pathlib import Path

import yaml

ROOT = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parents[3]
SPEC = importlib.util.spec_from_file_location("run_facts", ROOT / "docs" / "tools" / "run_facts.py")
run_facts = importlib.util.module_from_spec(SPEC)
sys.modules["run_facts"] = run_facts  # dataclasses look their module up
SPEC.loader.exec_module(run_facts)

ROBOT = """name: test
body:
  diameter_m: 0.80
  mass_kg: 50.0
wheels:
  - {kind: steerable, chamber: 2, mount_radius_m: 0.26, radius_m: 0.05, friction_coefficient: 0.6}
  - {kind: steerable, chamber: 4, mount_radius_m: 0.26, radius_m: 0.05, friction_coefficient: 0.6}
  - {kind: steerable, chamber: 6, mount_radius_m: 0.26, radius_m: 0.05, friction_coefficient: 0.6}
gas:
  ambient_pressure_pa: 100000
"""


def write_run(path: Path, t_f_leak: list[tuple[float, float, float]], summary: dict) -> None:
    """A run directory with t_s, downforce_n, two leak columns (outer1 leaks as given, inner1
    never) and wheel loads; the robot file above."""
    path.mkdir(parents=True)
    (path / "robot.yaml").write_text(ROBOT)
    (path / "scenario.yaml").write_text(f"name: made-up\nrobot: {path / 'robot.yaml'}\n")
    with open(path / "trace.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["t_s", "downforce_n", "pr_pa", "leak_area_m2_outer1", "leak_area_m2_inner1",
                    "wheel1_normal_n", "wheel2_normal_n", "wheel3_normal_n"])
        for t, force, leak in t_f_leak:  # the reservoir's suction: 3 kPa off the crack, 1 kPa on it
            w.writerow([t, force, 99000 if leak > 5e-5 else 97000, leak, 1e-5, 1, 2, 3])
    full = {"downforce_setpoint_n": 1000.0, "downforce_from_s": 1.0, "mean_downforce_n": 900.0,
            "max_pf_shift_m": 0.042, "slide_m": 0.00078, "slide_limit_m": 0.005, "slid": False,
            "outcome": "completed"}
    full.update(summary)
    (path / "summary.json").write_text(json.dumps(full))


DEFAULT_TRACE = [(0.0, 0.0, 1e-5), (0.5, 995.0, 1e-5), (0.75, 1050.0, 1e-5), (1.0, 1000.0, 1e-5),
                 (1.5, 700.0, 9e-5), (2.0, 1300.0, 2e-5), (2.5, 1000.0, 1e-5)]


def write_sweep(path: Path, outcomes: list[tuple[str, float | None, bool]]) -> None:
    """A sweep directory over run_facts.SWEEP_VALUES: (outcome, fell_at_s or None, slid) per
    variant; each variant's crack opens its first strip at 1.5 s (DEFAULT_TRACE)."""
    path.mkdir(parents=True)
    rows = []
    for i, (value, (outcome, fell_at_s, slid)) in enumerate(zip(run_facts.SWEEP_VALUES, outcomes)):
        name = f"{i:03d}_{run_facts.SWEEP_KEY}={value}"
        write_run(path / name, DEFAULT_TRACE, {"slide_m": 0.5 if slid else 0.001, "slid": slid, "fell_at_s": fell_at_s})
        fell = "true" if fell_at_s is not None else "false"
        rows.append([i, value, outcome, fell, 100.0 + i, 500.0 + i, 0.1, 0.2, 3.0, name,
                     "true" if slid else "false", 0.5 if slid else 0.001, 0.005, "true" if slid or fell == "true" else "false",
                     "" if fell_at_s is None else "%.17g" % fell_at_s, "", "", 0, 5 if fell == "true" else 0, "", "why"])
    with open(path / "sweep.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["variant", run_facts.SWEEP_KEY, "outcome", "fell", "min_downforce_n", "mean_downforce_n",
                    "max_pf_shift_m", "max_slip_mps", "wall_s", "dir", "slid", "slide_m", "slide_limit_m",
                    "adhesion_failed", "fell_at_s", "seal_over_nothing_at_s", "wheels_over_nothing_at_s",
                    "dropped_samples", "exit_code", "culprit", "reason"])
        w.writerows(rows)


class Facts(unittest.TestCase):
    def setUp(self):
        self.dir = Path(tempfile.mkdtemp(prefix="run-facts-test-"))

    def tearDown(self):
        shutil.rmtree(self.dir)

    def test_the_default_runs_facts_are_its_traces_and_summarys(self):
        write_run(self.dir / "run", DEFAULT_TRACE, {})
        text = run_facts.default_run_block(run_facts.Run.read(self.dir / "run"))
        self.assertIn("F reaches 99 % of its set-point of 1000 N at 0.5 s and overshoots it by at most 5.0 % while", text)
        self.assertIn("`outer1` leaks more than 5 times its basic leak) at 1.5 s and leaves the last (`outer1`) at 1.5 s", text)
        self.assertIn("suction falls from 3.0 kPa to 1.0 kPa (1.5 s)", text)
        self.assertIn("After the release at 1 s F stays between 700 N (1.5 s) and 1300 N (2 s, 30.0 % over the set-point)", text)
        self.assertIn("mean 900 N", text)
        self.assertIn("at times below the 818 N the wheels need", text)  # 50 kg * 9.81 / 0.6 > 700 N
        self.assertIn("up to 42 mm from the centre", text)
        self.assertIn("slides 0.78 mm (`slide_m`, within the 5 mm limit) and the run ends `completed`", text)

    def test_the_robots_picture_names_its_wheels_loads(self):
        write_run(self.dir / "run", [(0.0, 0.0, 1e-5), (5.0, 1000.0, 1e-5)], {})
        text = run_facts.robot_picture_block(run_facts.Run.read(self.dir / "run"))
        self.assertIn("F = 1000 N, and the wheels in chambers 2, 4 and 6 carry 1 N, 2 N and 3 N.", text)
        self.assertIn("](../deploy/doc/robot-ring.png)", text)

    def test_a_run_that_never_reaches_its_set_point_is_refused(self):
        write_run(self.dir / "run", [(t, 500.0, 1e-5) for t, _, _ in DEFAULT_TRACE], {})
        with self.assertRaisesRegex(run_facts.Failure, "never reaches 99 %"):
            run_facts.default_run_block(run_facts.Run.read(self.dir / "run"))

    def test_a_cell_that_is_no_number_is_named(self):
        write_run(self.dir / "run", DEFAULT_TRACE, {})
        trace = self.dir / "run" / "trace.csv"
        trace.write_text(trace.read_text().replace("1300.0", "oops", 1))
        with self.assertRaisesRegex(run_facts.Failure, r"trace.csv:7: downforce_n = 'oops'"):
            run_facts.Run.read(self.dir / "run")

    def test_the_sweep_table_has_a_row_per_variant_and_says_what_the_outcomes_say(self):
        # The made-up robot needs 818 N: 500 and 700 N are below it, 900 N falls after the crack
        # (1.5 s), 1500 N before it; 2200 N slides.
        write_sweep(self.dir / "sweep", [("fell", 1.0, True), ("fell", 2.0, False), ("fell", 2.5, False),
                                          ("fell", 1.0, False), ("completed", None, True)])
        text = run_facts.sweep_block(run_facts.read_sweep(self.dir / "sweep"))
        self.assertIn(run_facts.sweep_command(), text)
        for value in run_facts.SWEEP_VALUES:
            self.assertIn(f"| {value} N |", text)
        self.assertIn("| 900 N | fell at 2.5 s | 102 N | 502 N | 100 mm | 0.20 m/s | 1 mm (until the fall) |", text)
        self.assertIn("| 2200 N | completed, slid | 104 N | 504 N | 100 mm | 0.20 m/s | 500 mm |", text)
        self.assertIn("At 500 N, below the 818 N the wheels need, the robot slides from its release on and falls at 1 s; "
                      "at 700 N, below the 818 N the wheels need, it slides", text)
        self.assertIn("at 900 N it falls once the crack is under it (2.5 s); "
                      "at 1500 N it falls before the crack reaches it (1 s); "
                      "at 2200 N it stays on the wall but slides beyond the slide limit.", text)

    def test_variants_that_hold_are_named_together(self):
        write_sweep(self.dir / "sweep", [("completed", None, False)] * 5)
        text = run_facts.sweep_block(run_facts.read_sweep(self.dir / "sweep"))
        self.assertIn("At 500, 700, 900, 1500 and 2200 N the robot holds.", text)

    def test_a_sweep_of_other_values_than_the_readmes_command_is_refused(self):
        write_sweep(self.dir / "sweep", [("completed", None, False)] * 5)
        table = self.dir / "sweep" / "sweep.csv"
        table.write_text(table.read_text().replace(",500,", ",400,"))
        with self.assertRaisesRegex(run_facts.Failure, "expected"):
            run_facts.read_sweep(self.dir / "sweep")


    def test_a_row_that_does_not_say_what_its_summary_says_is_refused(self):
        write_sweep(self.dir / "sweep", [("completed", None, False)] * 4 + [("completed", None, True)])
        table = self.dir / "sweep" / "sweep.csv"
        lines = table.read_text().splitlines(keepends=True)
        table.write_text("".join(lines[:-1]) + lines[-1].replace(",true,", ",false,", 1))
        with self.assertRaisesRegex(run_facts.Failure, "does not say what its summary.json says"):
            run_facts.read_sweep(self.dir / "sweep")


class Blocks(unittest.TestCase):
    BLOCKS = {"a": "new A\n", "b": "new B\n"}

    def test_every_block_is_replaced_and_the_rest_kept(self):
        text = "x\n<!-- run-facts:a:begin -->\nold\n<!-- run-facts:a:end -->\ny\n<!-- run-facts:b:begin -->\n<!-- run-facts:b:end -->\n"
        seen = set()
        out = run_facts.rewritten(text, self.BLOCKS, Path("doc.md"), seen)
        self.assertEqual(out, "x\n<!-- run-facts:a:begin -->\nnew A\n<!-- run-facts:a:end -->\ny\n"
                              "<!-- run-facts:b:begin -->\nnew B\n<!-- run-facts:b:end -->\n")
        self.assertEqual(seen, {"a", "b"})
        self.assertEqual(run_facts.rewritten(out, self.BLOCKS, Path("doc.md"), set()), out)

    def test_an_unknown_block_is_refused(self):
        with self.assertRaisesRegex(run_facts.Failure, r"doc\.md: unknown run-facts block 'c'"):
            run_facts.rewritten("<!-- run-facts:c:begin -->\n<!-- run-facts:c:end -->\n", self.BLOCKS,
                                Path("doc.md"), set())

    def test_a_block_without_its_end_is_refused(self):
        with self.assertRaisesRegex(run_facts.Failure, "a:begin has no matching end"):
            run_facts.rewritten("<!-- run-facts:a:begin -->\nold\n", self.BLOCKS, Path("doc.md"), set())

    def test_check_finds_a_stale_block_and_a_stale_figure_and_writing_fixes_both(self):
        with tempfile.TemporaryDirectory() as tmp:
            root, runs = Path(tmp) / "root", Path(tmp) / "runs"
            (root / "docs").mkdir(parents=True)
            (root / "deploy" / "doc").mkdir(parents=True)
            write_run(runs / run_facts.DEFAULT_SCENARIO, DEFAULT_TRACE, {})
            write_run(runs / run_facts.ROBOT_SCENARIO, DEFAULT_TRACE, {})
            write_sweep(runs / "sweep", [("completed", None, False)] * 5)
            for run, name, committed in run_facts.FIGURES:
                (runs / run / name).parent.mkdir(parents=True, exist_ok=True)
                (runs / run / name).write_bytes(b"\x89PNG\r\n\x1a\n" + bytes(16) + name.encode())
                (root / committed).write_bytes(b"an old figure")
            marks = "".join(f"<!-- run-facts:{n}:begin -->\nstale\n<!-- run-facts:{n}:end -->\n"
                            for n in ("default-run", "sweep"))
            (root / "README.md").write_text("# r\n" + marks)
            (root / "docs" / "robot-files.md").write_text(
                "<!-- run-facts:robot-picture:begin -->\n<!-- run-facts:robot-picture:end -->\n")
            out = io.StringIO()
            with redirect_stdout(out):
                self.assertEqual(run_facts.update(root, runs, check=True), 1)
            self.assertIn("-stale", out.getvalue())
            self.assertIn("crack-descent-downforce.png: differs", out.getvalue())
            self.assertIn("(not a PNG committed", out.getvalue())
            self.assertEqual((root / "deploy/doc/robot-ring.png").read_bytes(), b"an old figure")  # untouched
            with redirect_stdout(io.StringIO()):
                self.assertEqual(run_facts.update(root, runs, check=False), 0)
                self.assertEqual(run_facts.update(root, runs, check=True), 0)
            self.assertNotIn("stale", (root / "README.md").read_text())

    def test_a_block_no_document_has_is_reported(self):
        with tempfile.TemporaryDirectory() as tmp:
            root, runs = Path(tmp) / "root", Path(tmp) / "runs"
            (root / "docs").mkdir(parents=True)
            write_run(runs / run_facts.DEFAULT_SCENARIO, DEFAULT_TRACE, {})
            write_run(runs / run_facts.ROBOT_SCENARIO, DEFAULT_TRACE, {})
            write_sweep(runs / "sweep", [("completed", None, False)] * 5)
            (root / "README.md").write_text("# nothing generated\n")
            with self.assertRaisesRegex(run_facts.Failure, "no document has the run-facts block"):
                run_facts.update(root, runs, check=True)


def robot_file(path: Path) -> dict:
    return robot_file_text(path.read_text())


def robot_file_text(text: str) -> dict:
    """`section.key` -> value of a robot file; list sections by item (`wheels[1].kind`)."""
    values = {}

    def walk(prefix: str, node) -> None:
        if isinstance(node, dict):
            for key, value in node.items():
                walk(f"{prefix}.{key}" if prefix else str(key), value)
        elif isinstance(node, list) and node and isinstance(node[0], dict):
            for i, item in enumerate(node, 1):
                walk(f"{prefix}[{i}]", item)
        else:
            values[prefix] = node

    walk("", yaml.safe_load(text))
    return values


class TheCommittedDocuments(unittest.TestCase):
    def test_robot_files_md_gives_the_value_of_every_key_of_the_shipped_robot(self):
        shipped = robot_file(ROOT / "deploy" / "robots" / "cromsci.yaml")
        text = (ROOT / "docs" / "robot-files.md").read_text()
        example = text[text.index("## The default robot"):]
        block = re.search(r"```yaml\n(.*?)```", example, re.S).group(1)
        self.assertEqual(robot_file_text(block), shipped)

    def test_robot_files_md_derives_the_default_values_from_the_shipped_robot(self):
        r = {k: float(v) for k, v in robot_file(ROOT / "deploy" / "robots" / "cromsci.yaml").items()
             if isinstance(v, (int, float)) and not isinstance(v, bool)}
        text = (ROOT / "docs" / "robot-files.md").read_text()
        defaults = text[text.index("## Default values"):]
        r1, r2, n = r["chambers.centre_radius_m"], r["chambers.sealed_diameter_m"] / 2, r["chambers.count"]
        theta = 2 * math.pi / n
        expected = [
            f"{math.pi / n * (r2 ** 2 - r1 ** 2):.4f} m²",                      # a ring chamber's suction area
            f"{math.pi * r1 ** 2:.4f} m²",                                       # the centre's
            f"{math.pi * r2 ** 2:.3f} m²",                                       # all together
            f"{r2 * theta:.3f} m",                                               # an outer arc
            f"{r2 - r1:.2f} m",                                                  # a radial wall
            f"{r1 * theta:.3f} m",                                               # an inner arc
            f"{r2 * theta * r['sealing.basic_gap_m'] * 1e6:.1f} mm²",           # an outer arc's basic leak
            f"{r['valves.discharge_coefficient'] * r['valves.max_area_m2'] * 1e4:.1f} cm² effective",
            f"= {r['body.mass_kg'] * 9.81 / r['wheels[1].friction_coefficient']:.0f} N",   # m g / mu
            f"= {r['engines.dp_max_pa'] * math.pi * r2 ** 2 / 1e3:.2f} kN",   # the engines' most
            f"{r['adhesion.desired_downforce_n']:.0f} N",
        ]
        for figure in expected:
            self.assertIn(figure, defaults)

    def test_the_readme_is_a_guide_of_at_most_350_lines(self):
        lines = (ROOT / "README.md").read_text().count("\n")
        self.assertLessEqual(lines, 350)

    def test_every_generated_block_of_the_documents_is_one_the_script_writes(self):
        names = set()
        for path in run_facts.documents(ROOT):
            for match in run_facts.BLOCK_MARK.finditer(path.read_text()):
                names.add(match.group(1))
        self.assertEqual(names, {"default-run", "sweep", "robot-picture"})

    def test_the_python_example_of_controllers_md_is_the_shipped_file(self):
        text = (ROOT / "docs" / "controllers.md").read_text()
        start = text.index("```python\n", text.index("## A controller in Python")) + len("```python\n")
        example = text[start:text.index("```\n", start)]
        self.assertEqual(example, (ROOT / "services/controller/examples/python/my_controller.py").read_text())


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1])
