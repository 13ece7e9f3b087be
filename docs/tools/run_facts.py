#!/usr/bin/env python3
"""Figures the docs quote from runs, generated from those runs.

It runs the in-process reference runs the docs speak of (`climbsim-solo`, byte-identical to
the distributed runs and fast) and a sweep, and writes what they give into the generated blocks
of README.md and docs/*.md,

    <!-- run-facts:NAME:begin -->
    ...generated...
    <!-- run-facts:NAME:end -->

and the figures the docs show into deploy/doc/. With --check it writes nothing and fails (exit
1) when a committed block or figure differs from what the runs give, with a diff; the ctest
`docs.run_facts` does that, so a quoted figure cannot go stale.

    python3 docs/tools/run_facts.py --bin build/bin                 # run, then rewrite
    python3 docs/tools/run_facts.py --bin build/bin --check          # run, then compare
    python3 docs/tools/run_facts.py --runs DIR [--check]             # reuse DIR's runs

Python 3 standard library only. Exit codes: 0 all equal (or rewritten), 1 a difference,
2 bad arguments or a run that failed.
"""

from __future__ import annotations

import argparse
import csv
import difflib
import json
import re
import shutil
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[2]

#: The default run (README "The first run"): the scenario `./deploy/climbsim up` runs.
DEFAULT_SCENARIO = "crack-descent"
#: The run the robot's picture comes from: the robot upright (yaw 0), settled, on rough concrete.
ROBOT_SCENARIO = "hold-rough"
ROBOT_PICTURE_AT_S = 5
#: The sweep the README shows: the set-points of the reference controller on the default run.
SWEEP_KEY = "controller.downforce_n"
SWEEP_VALUES = ["500", "700", "900", "1500", "2200"]
SWEEP_JOBS = 2

#: Figures copied from the runs: (run, file in the run directory, committed file).
FIGURES = [
    (DEFAULT_SCENARIO, "plots/downforce.png", "deploy/doc/crack-descent-downforce.png"),
    (ROBOT_SCENARIO, f"plots/ring_{ROBOT_PICTURE_AT_S}s.png", "deploy/doc/robot-ring.png"),
]

#: Gravity the plots use for the downforce the wheels need, m g / mu [m/s^2].
GRAVITY_MPS2 = 9.81

BLOCK = re.compile(r"<!-- run-facts:([\w-]+):begin -->\n(.*?)<!-- run-facts:\1:end -->", re.S)
BLOCK_MARK = re.compile(r"<!-- run-facts:([\w-]+):(begin|end) -->")


class Failure(Exception):
    """A run that failed or input that does not read: one line, exit code 2."""


# ---------------------------------------------------------------- reading a run directory


@dataclass
class Run:
    """A run directory: its trace as columns, its summary, its resolved scenario's text."""

    path: Path
    columns: dict[str, list[float]]
    summary: dict
    scenario_text: str

    @classmethod
    def read(cls, path: Path) -> "Run":
        trace = path / "trace.csv"
        try:
            with open(trace, newline="") as f:
                rows = list(csv.reader(f))
            summary = json.loads((path / "summary.json").read_text())
            scenario_text = (path / "scenario.yaml").read_text()
        except (OSError, ValueError) as e:
            raise Failure(f"{path}: not a run directory ({e})") from None
        if len(rows) < 2:
            raise Failure(f"{trace}: no rows")
        header = rows[0]
        columns: dict[str, list[float]] = {name: [] for name in header}
        for line, row in enumerate(rows[1:], start=2):
            if len(row) != len(header):
                raise Failure(f"{trace}:{line}: {len(row)} cells, the header has {len(header)}")
            for name, cell in zip(header, row):
                try:
                    columns[name].append(float(cell))
                except ValueError:
                    raise Failure(f"{trace}:{line}: {name} = {cell!r}: not a number") from None
        return cls(path, columns, summary, scenario_text)

    def column(self, name: str) -> list[float]:
        if name not in self.columns:
            raise Failure(f"{self.path / 'trace.csv'}: no column {name!r}")
        return self.columns[name]

    def scenario_value(self, key: str) -> str:
        """A top-level `key: value` of the resolved scenario (robot, name)."""
        match = re.search(rf"^{re.escape(key)}:\s*(.+?)\s*$", self.scenario_text, re.M)
        if not match:
            raise Failure(f"{self.path / 'scenario.yaml'}: no {key!r}")
        return match.group(1).strip("'\"")


def robot_value(robot_text: str, section: str, key: str) -> float:
    """`key` of `section:` in a robot file; for a list section (wheels) its first item's."""
    try:
        value = yaml.safe_load(robot_text)[section]
        if isinstance(value, list):
            value = value[0]
        return float(value[key])
    except (yaml.YAMLError, KeyError, IndexError, TypeError, ValueError):
        raise Failure(f"robot file: no {section}.{key}") from None


def robot_text(run: Run) -> str:
    """The text of the run's robot file (the resolved scenario names it absolute)."""
    robot_path = Path(run.scenario_value("robot"))
    try:
        return robot_path.read_text()
    except OSError as e:
        raise Failure(f"{robot_path}: {e.strerror}") from None


def holding_downforce_n(run: Run) -> float:
    """m g / mu of the run's robot: the downforce the wheels need on a vertical wall [N]."""
    text = robot_text(run)
    return robot_value(text, "body", "mass_kg") * GRAVITY_MPS2 / robot_value(text, "wheels", "friction_coefficient")


# ---------------------------------------------------------------- numbers as the docs write them


def newton(value: float) -> str:
    return f"{value:.0f} N"


def seconds(value: float) -> str:
    return f"{value:.2f}".rstrip("0").rstrip(".") + " s"


def millimetres(value_m: float) -> str:
    """Whole millimetres from 10 mm on, else at most two decimals without trailing zeros."""
    mm = value_m * 1e3
    return f"{mm:.0f} mm" if mm >= 10 else f"{mm:.2f}".rstrip("0").rstrip(".") + " mm"


def kilopascal(value_pa: float) -> str:
    return f"{value_pa / 1e3:.1f} kPa"


def percent(value: float) -> str:
    return f"{abs(value) * 100:.1f} %"


def metres_as_words(value_m: float) -> str:
    return millimetres(value_m) if value_m < 1.0 else f"{value_m:.2f} m"


# ---------------------------------------------------------------- the blocks


def leak_window(run: Run, factor: float = 5.0) -> tuple[float, str, float, str] | None:
    """When the first sealing segment leaks more than `factor` times its basic leak (row 0), and
    when the last one stops: (first time, its segment, last time, its segment), or None."""
    t = run.column("t_s")
    first = last = None
    for name, values in run.columns.items():
        if not name.startswith("leak_area_m2_"):
            continue
        basic = values[0]
        hits = [i for i, v in enumerate(values) if v > factor * basic]
        if not hits:
            continue
        segment = name.removeprefix("leak_area_m2_")
        if first is None or hits[0] < first[0]:
            first = (hits[0], segment)
        if last is None or hits[-1] > last[0]:
            last = (hits[-1], segment)
    if first is None or last is None:
        return None
    return t[first[0]], first[1], t[last[0]], last[1]


def default_run_block(run: Run) -> str:
    """The README's facts of the default run."""
    s = run.summary
    t = run.column("t_s")
    f = run.column("downforce_n")
    set_point = float(s["downforce_setpoint_n"])
    hold_s = float(s.get("downforce_from_s", 0.0))
    reached = next((i for i, v in enumerate(f) if v >= 0.99 * set_point), None)
    held = [i for i, ti in enumerate(t) if ti < hold_s]
    after = [i for i, ti in enumerate(t) if ti >= hold_s]
    if reached is None or not held or not after:
        raise Failure(f"{run.path}: the downforce never reaches 99 % of its set-point {set_point} N")
    peak_held = max(held, key=lambda i: f[i])
    low = min(after, key=lambda i: f[i])
    high = max(after, key=lambda i: f[i])
    window = leak_window(run)
    lines = [
        f"In this run F reaches 99 % of its set-point of {newton(set_point)} at {seconds(t[reached])} and "
        f"overshoots it by at most {percent(f[peak_held] / set_point - 1)} while the robot is held.",
    ]
    if window:
        first, last = t.index(window[0]), t.index(window[2])
        ambient_pa = robot_value(robot_text(run), "gas", "ambient_pressure_pa")
        suction = [ambient_pa - p for p in run.column("pr_pa")]
        lowest = min(range(first, last + 1), key=lambda i: suction[i])
        lines.append(
            f"The crack opens the first strip (`{window[1]}` leaks more than 5 times its basic leak) "
            f"at {seconds(window[0])} and leaves the last (`{window[3]}`) at {seconds(window[2])}; meanwhile "
            f"the reservoir's suction falls from {kilopascal(suction[max(first - 1, 0)])} to {kilopascal(suction[lowest])} "
            f"({seconds(t[lowest])})."
        )
    needed_n = holding_downforce_n(run)
    margin = "always above" if f[low] > needed_n else "at times below"
    lines.append(
        f"After the release at {seconds(hold_s)} F stays between {newton(f[low])} ({seconds(t[low])}) "
        f"and {newton(f[high])} ({seconds(t[high])}, {percent(f[high] / set_point - 1)} over the set-point), "
        f"mean {newton(float(s['mean_downforce_n']))}, {margin} the {newton(needed_n)} "
        f"the wheels need (m g / mu); P_F moves up to {millimetres(float(s['max_pf_shift_m']))} from the centre."
    )
    slid = "beyond" if s["slid"] else "within"
    lines.append(
        f"The robot slides {millimetres(float(s['slide_m']))} (`slide_m`, {slid} the "
        f"{millimetres(float(s['slide_limit_m']))} limit) and the run ends `{s['outcome']}`."
    )
    return "\n".join(lines) + "\n"


@dataclass
class Variant:
    """One variant of the sweep: its row of sweep.csv and what its run directory adds."""

    value: str
    outcome: str
    fell: bool
    min_downforce_n: float
    mean_downforce_n: float
    max_pf_shift_m: float
    max_slip_mps: float
    slide_m: float
    slid: bool
    fell_at_s: float | None  # the fall's time (summary.json)
    crack_at_s: float | None  # when the crack opens its first strip (its trace), None: never
    needed_n: float  # m g / mu of its robot


def fell_at_cell(summary: dict) -> str:
    """summary.json's fell_at_s as sweep.csv writes it (%.17g; empty for null)."""
    t = summary.get("fell_at_s")
    return "" if t is None else "%.17g" % t


def read_sweep(path: Path) -> list[Variant]:
    table = path / "sweep.csv"
    try:
        with open(table, newline="") as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        raise Failure(f"{table}: {e.strerror}") from None
    variants = []
    for row in rows:
        if SWEEP_KEY not in row:
            raise Failure(f"{table}: no column {SWEEP_KEY!r}")
        run = Run.read(path / row["dir"])
        summary = run.summary
        window = leak_window(run)
        if row.get("slid") != str(summary["slid"]).lower() or row.get("fell_at_s") != fell_at_cell(summary):
            raise Failure(f"{table}: the row of {row['dir']} does not say what its summary.json says")
        fell_at = row["fell_at_s"]
        variants.append(Variant(row[SWEEP_KEY], row["outcome"], row["fell"] == "true", float(row["min_downforce_n"]),
                                float(row["mean_downforce_n"]), float(row["max_pf_shift_m"]),
                                float(row["max_slip_mps"]), float(row["slide_m"]), row["slid"] == "true",
                                float(fell_at) if fell_at else None, window[0] if window else None,
                                holding_downforce_n(run)))
    if [v.value for v in variants] != SWEEP_VALUES:
        raise Failure(f"{table}: variants {[v.value for v in variants]}, expected {SWEEP_VALUES}")
    return variants


def sweep_command() -> str:
    return (f"./deploy/climbsim sweep {DEFAULT_SCENARIO} --set {SWEEP_KEY}={','.join(SWEEP_VALUES)} "
            f"-j {SWEEP_JOBS} --out /tmp/sweep1")


def fall_clause(v: Variant) -> str:
    """How variant v fell, for the sweep's verdict ("it": the robot, named before)."""
    when = seconds(v.fell_at_s) if v.fell_at_s is not None else "the end"
    if float(v.value) < v.needed_n:
        return f"at {v.value} N, below the {newton(v.needed_n)} the wheels need, it slides from its release on and falls at {when}"
    if v.crack_at_s is not None and v.fell_at_s is not None and v.fell_at_s >= v.crack_at_s:
        return f"at {v.value} N it falls once the crack is under it ({when})"
    return f"at {v.value} N it falls before the crack reaches it ({when})"


def sweep_block(variants: list[Variant]) -> str:
    """The README's sweep: the command, a row per variant from sweep.csv and its run directory,
    and what the outcomes say."""
    lines = [
        "```",
        sweep_command(),
        "```",
        "",
        f"| `{SWEEP_KEY}` | outcome | least F after the hold | mean F | P_F off centre | fastest slip | slide |",
        "| --- | --- | --- | --- | --- | --- | --- |",
    ]
    for v in variants:
        outcome = v.outcome + (", slid" if v.slid and not v.fell else "")
        if v.fell and v.fell_at_s is not None:
            outcome += f" at {seconds(v.fell_at_s)}"
        slide = metres_as_words(v.slide_m) + (" (until the fall)" if v.fell else "")
        lines.append(f"| {v.value} N | {outcome} | {newton(v.min_downforce_n)} | {newton(v.mean_downforce_n)} | "
                     f"{v.max_pf_shift_m * 1e3:.0f} mm | {v.max_slip_mps:.2f} m/s | {slide} |")

    slid = [v.value for v in variants if v.slid and not v.fell]
    held = [v.value for v in variants if not v.fell and not v.slid]
    verdicts = [fall_clause(v) for v in variants if v.fell]
    if slid:
        verdicts.append(f"at {listed(slid, ' N')} it stays on the wall but slides beyond the slide limit")
    if held:
        verdicts.append(f"at {listed(held, ' N')} it holds")
    text = "; ".join(verdicts).replace(" it ", " the robot ", 1)
    lines += ["", text[0].upper() + text[1:] + "."]
    return "\n".join(lines) + "\n"


def listed(items: list[str], unit: str = "") -> str:
    """'a', 'a and b', 'a, b and c', the unit after the last."""
    text = items[0] if len(items) == 1 else ", ".join(items[:-1]) + " and " + items[-1]
    return text + unit


def robot_picture_block(run: Run) -> str:
    """docs/robot-files.md's picture of the shipped robot."""
    t = run.column("t_s")
    i = min(range(len(t)), key=lambda k: abs(t[k] - ROBOT_PICTURE_AT_S))
    try:
        chambers = [str(w["chamber"]) for w in yaml.safe_load(robot_text(run))["wheels"]]
    except (yaml.YAMLError, KeyError, TypeError):
        raise Failure("robot file: no wheels[i].chamber") from None
    loads = [newton(run.column(f"wheel{w}_normal_n")[i]) for w in range(1, len(chambers) + 1)]
    return (
        f"![The shipped robot at {ROBOT_PICTURE_AT_S} s of {ROBOT_SCENARIO}](../deploy/doc/robot-ring.png)\n"
        "\n"
        f"The shipped robot from outside, at {ROBOT_PICTURE_AT_S} s of `{ROBOT_SCENARIO}` (yaw 0: its x points to the "
        "right, up in the picture is up the wall), as `climbsim-plot` draws it (`plots/ring_<t>s.png`): the "
        "chambers numbered and coloured by pressure, each wheel a circle whose area grows with its normal load, "
        f"P_F in red. Here F = {newton(run.column('downforce_n')[i])}, and the wheels in chambers "
        f"{listed(chambers)} carry {listed(loads)}.\n"
    )


def generate(runs: Path) -> dict[str, str]:
    """Every block, from the run directories under `runs`."""
    default = Run.read(runs / DEFAULT_SCENARIO)
    robot = Run.read(runs / ROBOT_SCENARIO)
    return {
        "default-run": default_run_block(default),
        "sweep": sweep_block(read_sweep(runs / "sweep")),
        "robot-picture": robot_picture_block(robot),
    }


# ---------------------------------------------------------------- running, rewriting, checking


def run_all(bin_dir: Path, runs: Path) -> None:
    """The runs the blocks come from, into `runs` (emptied first)."""
    if runs.exists():
        shutil.rmtree(runs)
    runs.mkdir(parents=True)
    commands = [
        [bin_dir / "climbsim-solo", DEFAULT_SCENARIO, "--out", runs / DEFAULT_SCENARIO],
        [bin_dir / "climbsim-solo", ROBOT_SCENARIO, "--out", runs / ROBOT_SCENARIO],
        [bin_dir / "climbsim-sweep", DEFAULT_SCENARIO, "--set", f"{SWEEP_KEY}={','.join(SWEEP_VALUES)}",
         "-j", str(SWEEP_JOBS), "--out", runs / "sweep"],
    ]
    for command in commands:
        args = [str(a) for a in command]
        print("run_facts: " + " ".join(args), flush=True)
        done = subprocess.run(args, capture_output=True, text=True)
        if done.returncode != 0:
            raise Failure(f"{' '.join(args)}: exit code {done.returncode}\n{done.stderr[-3000:]}")


def documents(root: Path) -> list[Path]:
    return [root / "README.md"] + sorted((root / "docs").glob("*.md"))


def rewritten(text: str, blocks: dict[str, str], where: Path, seen: set[str]) -> str:
    """`text` with every run-facts block replaced; unknown names and unpaired marks fail."""
    marks = [(m.group(1), m.group(2)) for m in BLOCK_MARK.finditer(text)]
    for i in range(0, len(marks), 2):
        pair = marks[i:i + 2]
        if len(pair) != 2 or pair[0][1] != "begin" or pair[1] != (pair[0][0], "end"):
            raise Failure(f"{where}: run-facts mark {marks[i][0]}:{marks[i][1]} has no matching end")

    def replace(match: re.Match) -> str:
        name = match.group(1)
        if name not in blocks:
            raise Failure(f"{where}: unknown run-facts block {name!r} (known: {', '.join(sorted(blocks))})")
        seen.add(name)
        return f"<!-- run-facts:{name}:begin -->\n{blocks[name]}<!-- run-facts:{name}:end -->"

    return BLOCK.sub(replace, text)


def update(root: Path, runs: Path, check: bool) -> int:
    blocks = generate(runs)
    seen: set[str] = set()
    differences = 0
    for path in documents(root):
        text = path.read_text()
        new = rewritten(text, blocks, path, seen)
        if new == text:
            continue
        if check:
            differences += 1
            sys.stdout.writelines(difflib.unified_diff(text.splitlines(True), new.splitlines(True),
                                                       f"{path.relative_to(root)} (committed)",
                                                       f"{path.relative_to(root)} (from the runs)"))
        else:
            path.write_text(new)
            print(f"run_facts: rewrote {path.relative_to(root)}")
    missing = sorted(set(blocks) - seen)
    if missing:
        raise Failure(f"no document has the run-facts block(s) {', '.join(missing)}")
    for run, name, committed in FIGURES:
        made = runs / run / name
        target = root / committed
        if not made.is_file():
            raise Failure(f"{made}: the run drew no such figure")
        if target.is_file() and target.read_bytes() == made.read_bytes():
            continue
        if check:
            differences += 1
            print(f"{committed}: differs from {made} ({png_size(target)} committed, {png_size(made)} from the run)")
        else:
            shutil.copyfile(made, target)
            print(f"run_facts: wrote {committed}")
    if differences:
        print(f"run_facts: {differences} difference(s): regenerate with "
              "`python3 docs/tools/run_facts.py --bin build/bin` and commit the result")
        return 1
    print("run_facts: every generated block and figure equals what the runs give")
    return 0


def png_size(path: Path) -> str:
    """'W x H px' from a PNG's header, or why not."""
    try:
        head = path.read_bytes()[:24]
    except OSError:
        return "missing"
    if head[:8] != b"\x89PNG\r\n\x1a\n":
        return "not a PNG"
    return f"{int.from_bytes(head[16:20], 'big')} x {int.from_bytes(head[20:24], 'big')} px"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--bin", type=Path, help="the build's bin directory: run the runs first")
    parser.add_argument("--runs", type=Path, help="where the runs are (with --bin: are made; default build/run-facts)")
    parser.add_argument("--root", type=Path, default=ROOT, help="the checkout (default: this script's)")
    parser.add_argument("--check", action="store_true", help="compare, write nothing; exit 1 on a difference")
    args = parser.parse_args(argv)
    runs = args.runs or (args.bin.parent / "run-facts" if args.bin else None)
    if runs is None:
        parser.error("give --bin (run the runs) or --runs (reuse them)")
    try:
        if args.bin:
            run_all(args.bin, runs)
        return update(args.root, runs, args.check)
    except Failure as e:
        print(f"run_facts: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
