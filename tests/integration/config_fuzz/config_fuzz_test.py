"""A fuzzer of the files a user writes: scenario, robot, compose and scene files, each mutated at
random (a value replaced by a huge, negative, non-numeric, empty, nested or very long one; a
line dropped or doubled; an attribute of the scene XML changed) and checked with
`climbsim-compose run SCENARIO -f COMPOSE --check`. Every case must end within its time limit
with exit code 0 or 2, and a refusal must be at most 21 lines, each at most 400 characters,
each naming a file.

    python3 config_fuzz_test.py ROOT BUILD [--cases N] [--seed S]

A fixed seed and a few dozen cases run in CI; more with --cases.
"""

import argparse
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

ARGS = argparse.Namespace(root=None, build=None, cases=36, seed=1)

VALUES = ["18446744073709551616", "-1", "0", "1e308", "-1e308", ".nan", ".inf", "9.9e99", "abc", "''", "[]",
          "{}", "[1, [2, [3]]]", "{a: {b: c}}", "null", "true", "0x10", "1_000", "x" * 5000, "'" + "y" * 100000 + "'",
          "-0", "1e-320", "2.5", "7", "&a [*a]", "!!binary aGk="]
XML_VALUES = ["", "nan", "1e308", "-1", "0 0 0 0 0 0 0", "a b c", "ROOT:ROOT", "ROBOT", "../../../etc/passwd",
              "x" * 5000, "meshes/missing.ply", "walls/pylon_blocks.xml", "1 2", "-3", "-1", "deg"]


def mutate_yaml(text: str, rng: random.Random) -> str:
    lines = text.splitlines()
    candidates = [i for i, line in enumerate(lines) if re.search(r"\w+:\s*\S", line) and not line.lstrip().startswith("#")]
    i = rng.choice(candidates)
    kind = rng.randrange(6)
    if kind == 0:
        del lines[i]
    elif kind == 1:
        lines.insert(i, lines[i])
    elif kind == 2:
        # A value in a flow mapping or after the key.
        matches = list(re.finditer(r"(\w+):\s*([^,{}\[\]#\n]+)", lines[i]))
        m = rng.choice(matches)
        lines[i] = lines[i][:m.start(2)] + rng.choice(VALUES) + " " + lines[i][m.end(2):]
    elif kind == 3:
        lines[i] = re.sub(r"(\w+):", lambda m: m.group(1)[::-1] + ":", lines[i], count=1)
    elif kind == 4:
        lines.insert(rng.randrange(len(lines) + 1), f"{rng.choice(['extra', 'seed', 'name', 'clock'])}: {rng.choice(VALUES)}")
    else:
        lines[i] = lines[i][: rng.randrange(len(lines[i]) + 1)]
    return "\n".join(lines) + "\n"


def mutate_xml(text: str, rng: random.Random) -> str:
    attrs = list(re.finditer(r'(\w+)="([^"]*)"', text))
    kind = rng.randrange(4)
    if kind == 0:
        m = rng.choice(attrs)
        return text[:m.start(2)] + rng.choice(XML_VALUES) + text[m.end(2):]
    if kind == 1:  # a part twice: the same full name
        parts = re.findall(r"<part [^>]*/>", text)
        part = rng.choice(parts)
        return text.replace(part, part + "\n    " + part, 1)
    if kind == 2:
        return text[: rng.randrange(len(text))]
    m = rng.choice(attrs)
    return text[:m.start()] + text[m.end():]


class ConfigFuzz(unittest.TestCase):
    def test_mutated_files_end_in_a_short_refusal_or_pass(self):
        root, build = Path(ARGS.root), Path(ARGS.build)
        rng = random.Random(ARGS.seed)
        work = Path(tempfile.mkdtemp(prefix="climbsim-fuzz-"))
        scenes = build / "scenes"
        try:
            counts = {"ok": 0, "refused": 0}
            for case in range(ARGS.cases):
                d = work / f"case{case}"
                (d / "scenes").mkdir(parents=True)
                shutil.copy(scenes / "pylon.xml", d / "scenes/pylon.xml")
                shutil.copytree(scenes / "walls", d / "scenes/walls")
                (d / "scenes/meshes").symlink_to(scenes / "meshes")  # 37 MB: shared, never mutated
                (d / "robots").mkdir()
                shutil.copy(root / "deploy/robots/cromsci.yaml", d / "robots/cromsci.yaml")
                scenario = (root / "deploy/scenarios/crack-descent.yaml").read_text()
                scenario = scenario.replace("$BUILD/scenes/pylon.xml", str(d / "scenes/pylon.xml"))
                scenario = scenario.replace("robot: cromsci", f"robot: {d / 'robots/cromsci.yaml'}")
                compose = (root / "deploy/compose.yaml").read_text().replace(
                    "scenarios/crack-descent.yaml", str(d / "scenario.yaml"))
                target = rng.choice(["scenario", "robot", "compose", "scene"])
                if target == "scenario":
                    scenario = mutate_yaml(scenario, rng)
                elif target == "robot":
                    (d / "robots/cromsci.yaml").write_text(mutate_yaml((d / "robots/cromsci.yaml").read_text(), rng))
                elif target == "compose":
                    compose = mutate_yaml(compose, rng)
                else:
                    scene = rng.choice([d / "scenes/pylon.xml", d / "scenes/walls/pylon_blocks.xml"])
                    scene.write_text(mutate_xml(scene.read_text(), rng))
                (d / "scenario.yaml").write_text(scenario)
                (d / "compose.yaml").write_text(compose)
                args = [str(build / "bin/climbsim-compose"), "--root", str(root), "--build", str(build), "run",
                        str(d / "scenario.yaml"), "-f", str(d / "compose.yaml"), "--check"]
                try:
                    r = subprocess.run(args, capture_output=True, text=True, timeout=120, errors="replace")
                except subprocess.TimeoutExpired:
                    self.fail(f"case {case} ({target}) hangs: {d}")
                where = f"case {case} ({target}), files in {d}:\n{r.stderr[-2000:]}"
                self.assertIn(r.returncode, (0, 2), where)
                if r.returncode == 0:
                    counts["ok"] += 1
                    self.assertIn("ok: ", r.stdout, where)
                    shutil.rmtree(d)
                    continue
                counts["refused"] += 1
                errors = [line for line in r.stderr.splitlines() if line.strip()]
                self.assertGreaterEqual(len(errors), 1, where)
                self.assertLessEqual(len(errors), 21, where)
                for line in errors:
                    self.assertLessEqual(len(line), 400, where)
                    self.assertRegex(line, r"(/|--set|climbsim-compose)", where)
                shutil.rmtree(d)
            print(f"fuzz: {ARGS.cases} cases (seed {ARGS.seed}): {counts['ok']} accepted, {counts['refused']} refused")
        finally:
            shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("root")
    parser.add_argument("build")
    parser.add_argument("--cases", type=int, default=36)
    parser.add_argument("--seed", type=int, default=1)
    ARGS = parser.parse_args()
    unittest.main(argv=sys.argv[:1], verbosity=2)
