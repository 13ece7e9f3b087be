"""run.mcap of a solo run (climbsim-solo) read with PyPI `mcap` and the Python package's own
types against trace.csv at every step; climbsim-mcap-check on it, on a copy cut short and on a
file that is no recording; a run with recording.depth_images holds every depth frame
(docs/recordings.md)."""

import json
import os
import re
import subprocess
import sys
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
import mcap_depth_images  # noqa: E402
import mcap_trace  # noqa: E402

BUILD = Path(os.environ["CLIMBSIM_BUILD_DIR"])
LAYOUT = Path(__file__).resolve().parents[3] / "deploy" / "foxglove" / "climbsim-layout.json"
BIN = BUILD / "bin"
RUNS = BUILD / "test-runs"


def solo(tag: str, *args: str) -> Path:
    out = RUNS / tag
    result = subprocess.run([str(BIN / "climbsim-solo"), *args, "--out", str(out), "--no-plots"],
                            capture_output=True, text=True, timeout=600)
    assert result.returncode == 0, result.stdout + result.stderr
    return out


def mcap_check(path: Path) -> subprocess.CompletedProcess:
    return subprocess.run([str(BIN / "climbsim-mcap-check"), str(path)], capture_output=True, text=True, timeout=60)


class SoloRecording(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        # Each test of this class is its own ctest entry, and ctest may run them side by side:
        # each process its own run directory.
        cls.run_dir = solo(f"mcap-solo-crack-descent-{os.getpid()}", "crack-descent")

    def test_every_channel_decodes_to_the_traces_values_at_every_step(self):
        rec = mcap_trace.check_closed_run(self.run_dir)
        self.assertEqual(rec.metadata["run"]["runner"], "solo")
        for topic, (name, encoding, text) in rec.schemas.items():
            self.assertEqual(encoding, "omgidl")
            self.assertIn("struct " + name.split("::")[1] + " {", text, topic)

    def test_mcap_check_counts_the_messages_of_a_closed_file(self):
        result = mcap_check(self.run_dir / "run.mcap")
        self.assertEqual(result.returncode, 0, result.stderr)
        rec = mcap_trace.read_recording(self.run_dir / "run.mcap")
        lines = result.stdout.splitlines()
        self.assertIn(": closed, ", lines[0])
        for topic in rec.raw:
            row = [line.split() for line in lines if line.startswith(topic + " ")]
            self.assertEqual(len(row), 1, topic)
            self.assertEqual(int(row[0][2]), len(rec.raw[topic]), topic)

    def test_a_file_cut_short_or_no_recording_is_one_line_and_exit_2(self):
        data = (self.run_dir / "run.mcap").read_bytes()
        cut = RUNS / "mcap-solo-cut.mcap"
        cut.write_bytes(data[: len(data) // 2])
        for path, says in ((cut, "it reads up to there"), (self.run_dir / "trace.csv", "not an MCAP file"),
                           (RUNS / "no-such-file.mcap", "cannot read")):
            result = mcap_check(path)
            self.assertEqual(result.returncode, 2, path)
            self.assertEqual(result.stdout, "", path)
            self.assertEqual(len(result.stderr.strip().splitlines()), 1, result.stderr)
            self.assertIn(says, result.stderr)
        # What it still holds decodes to the trace's values up to there.
        rec = mcap_trace.read_recording(cut)
        self.assertFalse(rec.complete)
        self.assertGreater(rec.last_log_time_ns, 5_000_000_000)
        mcap_trace.compare_with_trace(rec, self.run_dir / "trace.csv", up_to_ns=rec.data_end_ns())

    def test_the_foxglove_layouts_topics_and_plot_paths_are_in_the_recording(self):
        layout = json.loads(LAYOUT.read_text())
        rec = mcap_trace.read_recording(self.run_dir / "run.mcap")
        three_d = layout["configById"]["3D!climbsim"]
        for topic in three_d["topics"]:
            # foxglove/depth_image: only with recording.depth_images (SoloDepthImages checks it)
            if topic not in ("foxglove/depth_grid", "foxglove/depth_image"):
                self.assertIn(topic, rec.raw, topic)
        self.assertEqual(three_d["followTf"], "robot")
        paths = [p["value"] for key, c in layout["configById"].items() if key.startswith("Plot!") for p in c["paths"]]
        self.assertGreaterEqual(len(paths), 20)
        for path in paths:
            m = re.fullmatch(r'"([^"]+)"((?:\.\w+|\[\d+\])+)', path)
            self.assertIsNotNone(m, path)
            topic, fields = m.group(1), m.group(2)
            value = next(iter(rec.messages[topic].values()))[-1][1]
            for name, index in re.findall(r"\.(\w+)|\[(\d+)\]", fields):
                value = getattr(value, name) if name else value[int(index)]
            self.assertIsInstance(value, float, path)


class SoloDepthImages(unittest.TestCase):
    def test_every_depth_frame_is_recorded_whole_and_is_the_image_the_scene_rendered(self):
        run_dir = solo(f"mcap-solo-depth-images-{os.getpid()}", "crack-descent", "--set", "duration_s=1",
                       "--set", "recording.depth_images=true")
        raw = mcap_depth_images.check_depth_images(run_dir)
        self.assertEqual(len(raw[mcap_depth_images.IMAGE_TOPIC]), 50)  # 1 s at 50 Hz
        # The layout's 3D panel names the channel (off: it lies where the reduced grid lies).
        topics = json.loads(LAYOUT.read_text())["configById"]["3D!climbsim"]["topics"]
        self.assertIn(mcap_depth_images.FOXGLOVE_TOPIC, topics)
        # The rest of the recording is as without the option.
        mcap_trace.check_closed_run(run_dir)
        check = mcap_check(run_dir / "run.mcap")
        self.assertEqual(check.returncode, 0, check.stderr)
        self.assertRegex(check.stdout, r"(?m)^scene/DepthImage\s+climbsim::DepthImage\s+50\s")
        # A value that is no boolean: one line naming the key, exit 2.
        bad = subprocess.run([str(BIN / "climbsim-solo"), "crack-descent", "--set", "recording.depth_images=often",
                              "--out", str(RUNS / "mcap-solo-depth-images-bad"), "--no-plots"],
                             capture_output=True, text=True, timeout=120)
        self.assertEqual(bad.returncode, 2, bad.stdout + bad.stderr)
        self.assertEqual(len(bad.stderr.strip().splitlines()), 1, bad.stderr)
        self.assertIn("recording.depth_images", bad.stderr)


if __name__ == "__main__":
    unittest.main()
