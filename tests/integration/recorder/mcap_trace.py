"""run.mcap read with the MCAP project's Python reader (PyPI `mcap`) and decoded with the
Python package's own types (climbsim_idl, generated from idl/*.idl by climbsim.idlgen for Cyclone
DDS), independently of climbsim's C++ writer, against the run's trace.csv row by row
(docs/recordings.md#what-runmcap-holds).
"""

from __future__ import annotations

import bisect
import csv
import json
import math
from dataclasses import dataclass, field
from pathlib import Path

import climbsim_idl
from mcap.reader import NonSeekingReader, make_reader

#: Topics whose producers give an initial state (StampedOutput::recordInitial): the first
#: message of a producer at t = 0 is the trace's row 0.
TRACE_TOPICS = {"thermo/ChamberState", "thermo/AdhesionForce", "sealing/Leakage", "drive/RobotState", "drive/DriveState"}
TOPICS_WITH_INITIAL_STATE = {"thermo/ChamberState", "thermo/AdhesionForce", "drive/RobotState", "drive/DriveState"}


@dataclass
class Recording:
    """The decoded messages of a run.mcap, by topic then producer, in file order."""

    messages: dict[str, dict[str, list[tuple[int, object]]]] = field(default_factory=dict)
    raw: dict[str, list[bytes]] = field(default_factory=dict)  # topic -> message data in file order
    schemas: dict[str, tuple[str, str, str]] = field(default_factory=dict)  # topic -> (name, encoding, text)
    metadata: dict[str, dict[str, str]] = field(default_factory=dict)
    complete: bool = True  # False: the reader stopped at a cut-short end
    last_log_time_ns: int = -1

    def data_end_ns(self) -> int:
        """The time up to which every recorded DDS topic read to the trace has its messages: the
        earliest of their last log times (a cut-short file ends with some ahead of others)."""
        ends = [max(t for msgs in by_source.values() for t, _ in msgs)
                for topic, by_source in self.messages.items() if topic in TRACE_TOPICS and by_source]
        return min(ends) if ends else -1

    def count(self, topic: str) -> int:
        return sum(len(v) for v in self.messages.get(topic, {}).values())


def idl_type(schema_name: str):
    module, _, name = schema_name.partition("::")
    if module != "climbsim":
        raise AssertionError(f"schema {schema_name!r} is not a climbsim type")
    return getattr(climbsim_idl, name)


def read_recording(path: Path) -> Recording:
    """Every message of `path` from its start, without its summary: a cut-short file reads up to
    its last whole record."""
    rec = Recording()
    with open(path, "rb") as f:
        reader = NonSeekingReader(f, validate_crcs=True)
        try:
            for schema, channel, message in reader.iter_messages(log_time_order=False):  # file order
                if channel.topic not in rec.schemas:
                    rec.schemas[channel.topic] = (schema.name, schema.encoding, schema.data.decode())
                    if channel.message_encoding != "cdr" or schema.encoding != "omgidl":
                        raise AssertionError(f"{channel.topic}: {channel.message_encoding}/{schema.encoding}")
                rec.raw.setdefault(channel.topic, []).append(bytes(message.data))
                if not schema.name.startswith("climbsim::"):
                    continue  # the Foxglove channels: decoded by the Node test with Foxglove's libraries
                sample = idl_type(schema.name).deserialize(message.data)
                t_ns = getattr(sample, "t_ns", 0)  # RunStart: t = 0
                if message.log_time != t_ns or message.publish_time != t_ns:
                    raise AssertionError(f"{channel.topic}: log time {message.log_time} != t_ns {t_ns}")
                source = getattr(sample, "source", "clock")
                rec.messages.setdefault(channel.topic, {}).setdefault(source, []).append((message.log_time, sample))
                rec.last_log_time_ns = max(rec.last_log_time_ns, message.log_time)
        except Exception as e:  # noqa: BLE001 - the mcap reader's errors for a file cut short
            if isinstance(e, AssertionError):
                raise
            rec.complete = False
    if rec.complete:
        with open(path, "rb") as f:
            for record in make_reader(f).iter_metadata():
                rec.metadata[record.name] = dict(record.metadata)
    return rec


def held(messages: list[tuple[int, object]], t_ns: int, has_initial: bool):
    """The sample a recorder reads at the row of time t_ns: the producer's last sample stamped
    before t_ns (one-step lag), or at t = 0 its initial state."""
    times = [t for t, _ in messages]
    i = bisect.bisect_left(times, t_ns)
    if i > 0:
        return messages[i - 1][1]
    if has_initial and messages and messages[0][0] == 0:
        return messages[0][1]
    return None


def roll_pitch_yaw(q):
    w, x, y, z = q
    n = math.sqrt(w * w + x * x + y * y + z * z)
    w, x, y, z = w / n, x / n, y / n, z / n
    r00 = 1 - 2 * (y * y + z * z)
    r10 = 2 * (x * y + w * z)
    r20 = 2 * (x * z - w * y)
    r21 = 2 * (y * z + w * x)
    r22 = 1 - 2 * (x * x + y * y)
    return math.atan2(r21, r22), math.asin(max(-1.0, min(1.0, -r20))), math.atan2(r10, r00)


def same(a: float, b: float) -> bool:
    return (math.isnan(a) and math.isnan(b)) or a == b


def compare_with_trace(rec: Recording, trace: Path, up_to_ns: int | None = None) -> int:
    """Checks every row of `trace` (up to the time `up_to_ns`, inclusive) against the samples the
    recording says the recorder read; returns the number of rows checked. AssertionError names the
    row, the column and both values."""
    with open(trace, newline="") as f:
        rows = list(csv.reader(f))
    header, rows = rows[0], rows[1:]
    col = {name: i for i, name in enumerate(header)}
    segments = [c[len("leak_area_m2_"):] for c in header if c.startswith("leak_area_m2_")]
    wheels = len([c for c in header if c.endswith("_normal_n")])

    def topic(name):
        by_source = rec.messages.get(name, {})
        return [(src, msgs) for src, msgs in sorted(by_source.items())]

    checked = 0
    for r in rows:
        t_ns = round(float(r[0]) * 1e9)
        if up_to_ns is not None and t_ns > up_to_ns:
            break

        def expect(column, value, tolerance=0.0):
            cell = float(r[col[column]])
            ok = same(cell, value) if tolerance == 0.0 else abs(cell - value) <= tolerance
            if not ok:
                raise AssertionError(f"{trace}: t = {r[0]} s, {column}: trace {cell!r}, run.mcap {value!r}")

        def latest(name):
            found = [held(m, t_ns, name in TOPICS_WITH_INITIAL_STATE) for _, m in topic(name)]
            found = [s for s in found if s is not None]
            return found[-1] if found else None

        force = latest("thermo/AdhesionForce")
        if force is not None:
            expect("downforce_n", force.downforce_n)
            expect("pf_x_m", force.pf_x_m)
            expect("pf_y_m", force.pf_y_m)
            expect("downforce_setpoint_n", force.downforce_setpoint_n)
        state = latest("thermo/ChamberState")
        if state is not None:
            for i in range(7):
                expect(f"p{i + 1}_pa", state.pressure_pa[i])
                expect(f"valve{i + 1}", state.valve_opening[i])
            expect("pr_pa", state.pressure_pa[7])
        areas = {}
        for _, msgs in topic("sealing/Leakage"):
            part = held(msgs, t_ns, False)
            if part is not None:
                areas.update({s.segment: s.leak_area_m2 for s in part.segments})
        for seg in segments:
            if seg in areas:
                expect(f"leak_area_m2_{seg}", areas[seg])
        pose = latest("drive/RobotState")
        if pose is not None:
            for name, v in zip(("x_m", "y_m", "z_m"), pose.position_m):
                expect(name, v)
            for name, v in zip(("roll_rad", "pitch_rad", "yaw_rad"), roll_pitch_yaw(pose.orientation_wxyz)):
                expect(name, v, tolerance=1e-12)
        drive = latest("drive/DriveState")
        if drive is not None:
            for i in range(wheels):
                expect(f"wheel{i + 1}_normal_n", drive.wheels[i].normal_force_n)
                expect(f"wheel{i + 1}_slip_mps", drive.wheels[i].slip_mps)
        checked += 1
    return checked


def check_closed_run(run_dir: Path) -> Recording:
    """A finished run: every row of trace.csv, the clock's messages, the metadata."""
    rec = read_recording(run_dir / "run.mcap")
    assert rec.complete, f"{run_dir}/run.mcap does not read to its end"
    rows = compare_with_trace(rec, run_dir / "trace.csv")
    with open(run_dir / "trace.csv") as f:
        assert rows == sum(1 for _ in f) - 1, "every row checked"
    for t in ("thermo/ChamberState", "thermo/AdhesionForce", "sealing/Leakage", "drive/RobotState", "drive/DriveState"):
        assert rec.count(t) > 0, f"no message on {t}"
    assert rec.count("clock/RunStart") == 1 and rec.count("clock/Stop") == 1
    start = rec.messages["clock/RunStart"]["clock"][0][1]
    stop = rec.messages["clock/Stop"]["clock"][0][1]
    summary = json.loads((run_dir / "summary.json").read_text())
    assert stop.t_ns == round(summary["sim_s"] * 1e9) + start.dt_ns, (stop, summary["sim_s"])
    # summary.json as the recorder wrote it; the launcher adds what the services' lines say later.
    recorded = json.loads(rec.metadata["summary"]["summary.json"])
    for key in ("scenario", "steps", "sim_s", "outcome", "fell", "min_downforce_n", "mean_downforce_n", "slide_m"):
        assert recorded[key] == summary[key], (key, recorded[key], summary[key])
    assert rec.metadata["scenario"]["text"] == (run_dir / "scenario.yaml").read_text()
    assert "robot" in rec.metadata and rec.metadata["robot"]["text"]
    return rec
