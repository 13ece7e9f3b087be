"""run.mcap of distributed runs through the launcher (docs/recordings.md): the same samples as
trace.csv at every step and as the solo run of the same scenario, byte for byte; a recorder
killed with SIGKILL leaves a recording readable up to its last closed chunk; a replay plays the
recorded samples back byte for byte to a controller whose commands it records."""

import os
import shutil
import signal
import subprocess
import sys
import time
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "integration" / "recorder"))
import mcap_depth_images  # noqa: E402
import mcap_trace  # noqa: E402

ROOT = Path(os.environ["CLIMBSIM_ROOT"])
BUILD = Path(os.environ["CLIMBSIM_BUILD_DIR"])
BIN = BUILD / "bin"
RUNS = BUILD / "test-runs"
DATA_TOPICS = ("thermo/ChamberState", "thermo/AdhesionForce", "sealing/Leakage", "drive/RobotState", "drive/DriveState",
               "foxglove/transforms", "foxglove/robot")
SOLO_TOPICS = DATA_TOPICS + ("scene/DepthGrid", "foxglove/depth_grid")


def launcher(out: Path, *args: str) -> list[str]:
    shutil.rmtree(out, ignore_errors=True)  # no trace of an earlier run to mistake for this one's
    return [str(BIN / "climbsim-compose"), "--root", str(ROOT), "--build", str(BUILD), "run", *args, "--out", str(out)]


def last_trace_time_s(trace: Path) -> float:
    """Time of the last complete row (0 before the first)."""
    try:
        lines = trace.read_text().splitlines()
    except FileNotFoundError:
        return 0.0
    complete = [line for line in lines[1:] if lines and line.count(",") == lines[0].count(",")]
    return float(complete[-1].split(",")[0]) if complete else 0.0


def recorder_pids(out: Path) -> list[int]:
    """The climbsim-recorder processes writing into `out`."""
    pids = []
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            argv = (entry / "cmdline").read_bytes().split(b"\0")
        except OSError:
            continue
        if argv and argv[0].endswith(b"climbsim-recorder") and str(out).encode() in argv:
            pids.append(int(entry.name))
    return pids


class DistributedRecording(unittest.TestCase):
    def test_a_distributed_run_records_its_traces_samples_and_solos_bytes(self):
        out = RUNS / "mcap-distributed"
        result = subprocess.run(launcher(out, "crack-descent", "--set", "duration_s=4"),
                                capture_output=True, text=True, timeout=600)
        self.assertEqual(result.returncode, 0, result.stdout[-3000:] + result.stderr[-3000:])
        rec = mcap_trace.check_closed_run(out)
        self.assertEqual(rec.metadata["run"]["runner"], "launcher")
        self.assertTrue(rec.metadata["compose"]["file"].endswith("deploy/compose.yaml"))
        self.assertIn("recorder:", rec.metadata["compose"]["text"])
        self.assertGreater(rec.count("scene/DepthGrid"), 0)

        self.view_serves_the_recordings_depth_grids(out)

        solo_out = RUNS / "mcap-distributed-solo"
        result = subprocess.run([str(BIN / "climbsim-solo"), "crack-descent", "--set", "duration_s=4", "--out",
                                 str(solo_out), "--no-plots"], capture_output=True, text=True, timeout=600)
        self.assertEqual(result.returncode, 0, result.stderr[-3000:])
        solo = mcap_trace.read_recording(solo_out / "run.mcap")
        for topic in SOLO_TOPICS:
            self.assertEqual(len(rec.raw[topic]), len(solo.raw[topic]), topic)
            self.assertTrue(rec.raw[topic] == solo.raw[topic], f"{topic}: the messages differ from solo's")

    def test_mcap_depth_images_of_a_distributed_run_are_every_frame_and_solos_bytes(self):
        """recording.depth_images: the recorder reads scene/DepthImage beside the sealing and
        records every frame, the same messages as a solo run of the scenario."""
        sets = ["--set", "duration_s=1", "--set", "recording.depth_images=true"]
        out = RUNS / "mcap-distributed-depth-images"
        result = subprocess.run(launcher(out, "crack-descent", *sets), capture_output=True, text=True, timeout=600)
        self.assertEqual(result.returncode, 0, result.stdout[-3000:] + result.stderr[-3000:])
        raw = mcap_depth_images.check_depth_images(out)
        self.assertEqual(len(raw[mcap_depth_images.IMAGE_TOPIC]), 50)  # 1 s at 50 Hz
        mcap_trace.check_closed_run(out)
        solo_out = RUNS / "mcap-distributed-depth-images-solo"
        result = subprocess.run([str(BIN / "climbsim-solo"), "crack-descent", *sets, "--out", str(solo_out),
                                 "--no-plots"], capture_output=True, text=True, timeout=600)
        self.assertEqual(result.returncode, 0, result.stderr[-3000:])
        solo = mcap_depth_images.check_depth_images(solo_out)
        for topic, messages in raw.items():
            self.assertTrue(messages == solo[topic], f"{topic}: the messages differ from solo's")

    def view_serves_the_recordings_depth_grids(self, run_dir: Path):
        """`view` of the run without viewer/depth_grids.jsonl: the wall's relief from run.mcap; and
        a cut-short run.mcap is one line and exit 2."""
        copy = RUNS / "mcap-view"
        shutil.rmtree(copy, ignore_errors=True)
        shutil.copytree(run_dir, copy)
        shutil.rmtree(copy / "viewer", ignore_errors=True)
        viewer = subprocess.Popen([str(BIN / "climbsim-viewer"), "--replay", str(copy), "--port", "18765",
                                   "--port-tries", "50"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        try:
            line = ""
            for line in viewer.stdout:  # the event: the line that says what it serves
                if "replay of" in line or "error" in line:
                    break
            self.assertRegex(line, r"rows, [1-9]\d* depth grids", line)
        finally:
            viewer.terminate()
            viewer.wait(timeout=60)
        data = (copy / "run.mcap").read_bytes()
        (copy / "run.mcap").write_bytes(data[: len(data) // 3])
        result = subprocess.run([str(BIN / "climbsim-viewer"), "--replay", str(copy), "--port", "18765",
                                 "--port-tries", "50"], capture_output=True, text=True, timeout=60)
        self.assertEqual(result.returncode, 2, result.stdout + result.stderr)
        self.assertEqual(len((result.stdout + result.stderr).strip().splitlines()), 1, result.stdout + result.stderr)
        self.assertIn("run.mcap", result.stdout + result.stderr)

    def test_a_killed_recorder_leaves_a_recording_readable_up_to_its_last_closed_chunk(self):
        out = RUNS / "mcap-killed-recorder"
        run = subprocess.Popen(launcher(out, "crack-descent"), stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        try:
            # Wait for the event: the recorder's trace past 5 s of simulated time.
            deadline = time.monotonic() + 300
            while last_trace_time_s(out / "trace.csv") < 5.0:
                self.assertIsNone(run.poll(), "the run ended before 5 s")
                self.assertLess(time.monotonic(), deadline, "no trace rows past 5 s")
                time.sleep(0.05)
            pids = recorder_pids(out)
            self.assertEqual(len(pids), 1, pids)
            os.kill(pids[0], signal.SIGKILL)
            output, _ = run.communicate(timeout=300)
        finally:
            if run.poll() is None:
                run.kill()
                run.wait()
        self.assertNotEqual(run.returncode, 0, output[-3000:])

        check = subprocess.run([str(BIN / "climbsim-mcap-check"), str(out / "run.mcap")], capture_output=True,
                               text=True, timeout=60)
        self.assertEqual(check.returncode, 2, check.stdout)
        self.assertEqual(len(check.stderr.strip().splitlines()), 1, check.stderr)

        rec = mcap_trace.read_recording(out / "run.mcap")
        trace_end_s = last_trace_time_s(out / "trace.csv")
        lost_s = trace_end_s - rec.data_end_ns() * 1e-9
        # A chunk closes at each whole second; the sealing samples every 20 ms, the others every 5 ms.
        self.assertLessEqual(lost_s, 1.0 + 0.03, f"trace to {trace_end_s} s, run.mcap to {rec.data_end_ns()} ns")
        self.assertGreater(rec.data_end_ns(), 3_000_000_000)
        rows = mcap_trace.compare_with_trace(rec, out / "trace.csv", up_to_ns=rec.data_end_ns())
        self.assertGreater(rows, 600)


class Replay(unittest.TestCase):
    def replay(self, run_dir: Path, out: Path, *args: str) -> subprocess.CompletedProcess:
        shutil.rmtree(out, ignore_errors=True)
        return subprocess.run([str(ROOT / "deploy" / "climbsim"), "replay", str(run_dir), *args, "--out", str(out)],
                              capture_output=True, text=True, timeout=600,
                              env={**os.environ, "CLIMBSIM_BUILD_DIR": str(BUILD)})

    def test_a_replay_plays_the_recorded_samples_byte_for_byte_and_records_the_controllers_commands(self):
        original = RUNS / "mcap-replayed"
        result = subprocess.run(launcher(original, "crack-descent", "--set", "duration_s=3"),
                                capture_output=True, text=True, timeout=600)
        self.assertEqual(result.returncode, 0, result.stdout[-3000:] + result.stderr[-3000:])
        out = RUNS / "mcap-replay"
        result = self.replay(original, out)
        self.assertEqual(result.returncode, 0, result.stdout[-3000:] + result.stderr[-3000:])
        self.assertEqual((out / "trace.csv").read_bytes(), (original / "trace.csv").read_bytes())
        recorded = mcap_trace.read_recording(original / "run.mcap")
        replayed = mcap_trace.check_closed_run(out)
        for topic in DATA_TOPICS:
            self.assertTrue(replayed.raw[topic] == recorded.raw[topic], f"{topic}: the replayed samples differ")
        steps = len((original / "trace.csv").read_text().splitlines()) - 1
        for topic in ("controller/ValveCommand", "controller/EngineCommand", "controller/DriveCommand"):
            self.assertGreaterEqual(replayed.count(topic), steps - 1, topic)
        valves = replayed.messages["controller/ValveCommand"]["controller"]
        self.assertEqual(valves[-1][1].downforce_setpoint_n, 2200.0)

        # Only some topics: the recorder records those, the others have no producer.
        narrow = RUNS / "mcap-replay-thermo"
        result = self.replay(original, narrow, "--topics", "thermo/ChamberState,thermo/AdhesionForce")
        self.assertEqual(result.returncode, 0, result.stdout[-3000:] + result.stderr[-3000:])
        rec = mcap_trace.read_recording(narrow / "run.mcap")
        self.assertEqual(rec.raw["thermo/ChamberState"], recorded.raw["thermo/ChamberState"])
        self.assertEqual(rec.count("drive/RobotState"), 0)
        self.assertGreater(rec.count("controller/ValveCommand"), 0)

    def test_a_cut_short_recording_or_no_run_directory_is_one_line_and_exit_2(self):
        bad = RUNS / "mcap-replay-bad"
        shutil.rmtree(bad, ignore_errors=True)
        bad.mkdir(parents=True)
        (bad / "scenario.yaml").write_text("name: x\n")
        (bad / "run.mcap").write_bytes(b"\x89MCAP0\r\n" + b"\x01" * 40)
        for run_dir, says in ((bad, "run.mcap"), (RUNS / "no-such-run", "not a run directory")):
            result = self.replay(run_dir, RUNS / "mcap-replay-none")
            self.assertEqual(result.returncode, 2, result.stderr)
            errors = [line for line in result.stderr.splitlines() if "climbsim replay" in line or "mcap-check" in line]
            self.assertEqual(len(errors), 1, result.stderr)
            self.assertIn(says, errors[0])


if __name__ == "__main__":
    unittest.main()
