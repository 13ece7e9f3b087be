"""docs/controllers.md's Python controller, copied outside the checkout as the page says: the
shipped my_controller.py and the page's compose file in a folder of their own, the run started
from that folder, commands the valves of the closed loop (a whole distributed run of 2 s).

    python3 controller_example_test.py ROOT BUILD
"""

from __future__ import annotations

import csv
import re
import shutil
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

ROOT = (Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).parents[3]).resolve()
BUILD = (Path(sys.argv[2]) if len(sys.argv) > 2 else ROOT / "build").resolve()


def page_compose_file() -> str:
    text = (ROOT / "docs" / "controllers.md").read_text()
    block = re.search(r"<!-- compose-example:begin -->\n```yaml\n(.*?)```\n<!-- compose-example:end -->", text, re.S)
    if not block:
        raise AssertionError("docs/controllers.md has no compose-example block")
    return block.group(1)


def column(trace: Path, name: str) -> list[float]:
    with open(trace, newline="") as f:
        return [float(row[name]) for row in csv.DictReader(f)]


class PythonControllerOutsideTheCheckout(unittest.TestCase):
    def setUp(self):
        self.folder = Path(tempfile.mkdtemp(prefix="climbsim-my-controller-"))
        self.assertFalse(self.folder.resolve().is_relative_to(ROOT.resolve()))

    def tearDown(self):
        shutil.rmtree(self.folder, ignore_errors=True)

    def test_the_copied_example_commands_the_valves_from_its_own_folder(self):
        shutil.copy(ROOT / "services/controller/examples/python/my_controller.py", self.folder / "my_controller.py")
        (self.folder / "compose.yaml").write_text(page_compose_file())
        # `deploy/climbsim run ...` is setup, build, then this (the build is done).
        command = [str(BUILD / "bin" / "climbsim-compose"), "--root", str(ROOT), "--build", str(BUILD), "run",
                   "crack-descent", "-f", "compose.yaml", "--set", "controller={type: external}",
                   "--set", "duration_s=2", "--name", "docs-python-example", "--out", "run1"]
        done = subprocess.run(command, cwd=self.folder, capture_output=True, text=True, timeout=300)
        self.assertEqual(done.returncode, 0, done.stdout[-3000:] + done.stderr[-3000:])
        trace = self.folder / "run1" / "trace.csv"
        openings = set(column(trace, "valve1"))
        self.assertGreater(max(openings), 0.0, "the example never opened a valve")
        self.assertLessEqual(max(openings), 0.5, sorted(openings)[-5:])
        # Its SETPOINT_N reaches the trace, not the robot file's or the scenario's set-point.
        self.assertEqual(set(column(trace, "downforce_setpoint_n")[2:]), {2200.0})


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1])
