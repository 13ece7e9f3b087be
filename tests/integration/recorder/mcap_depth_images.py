"""The full-rate depth images of a run.mcap (the scenario's recording.depth_images,
docs/recordings.md#full-rate-depth-images), read with the MCAP project's Python reader (PyPI
`mcap`) and decoded with the Python package's own types (climbsim_idl), independently of
climbsim's writer: every frame the scene rendered and the recorder read is there once, whole, at
its own time, and is the image the scene rendered (its block means are the scene's own reduced
depth grid of that frame, scene/DepthGrid); its foxglove.Grid holds the same heights.
"""

from __future__ import annotations

import json
import struct
from array import array
from pathlib import Path

import climbsim_idl
from mcap.reader import make_reader

IMAGE_TOPIC = "scene/DepthImage"
GRID_TOPIC = "scene/DepthGrid"
FOXGLOVE_TOPIC = "foxglove/depth_image"


def expected_frame_steps(run_dir: Path, run_start) -> list[int]:
    """The steps of the frames a recorder reads: each due step of the scene (its roster entry's
    period and offset) before the recorder's last step (it reads a frame one step later)."""
    steps = json.loads((run_dir / "summary.json").read_text())["steps"]
    scene = [e for e in run_start.roster if e.participant == "scene"]
    assert len(scene) == 1, [e.participant for e in run_start.roster]
    period, offset = scene[0].period_steps, scene[0].offset_steps
    return [s for s in range(offset, steps - 1, period)]


def float32(value: float) -> float:
    """`value` rounded to the nearest float (as C++'s static_cast<float>)."""
    return struct.unpack("f", struct.pack("f", value))[0]


def block_means(heights: array, side: int, size: int) -> list[float]:
    """The size x size block means of a side x side image (row-major), each block summed row by
    row in double and rounded to float, as the scene reduces an image to its depth grid."""
    block = side // size
    means = []
    for gy in range(size):
        for gx in range(size):
            total = 0.0
            for y in range(gy * block, (gy + 1) * block):
                total += sum(heights[y * side + gx * block:y * side + (gx + 1) * block])
            means.append(float32(total / (block * block)))
    return means


def flipped_rows(heights: array, width: int, height: int) -> bytes:
    """The image's float32 bytes with its rows in reverse order (a foxglove.Grid's rows go up)."""
    return b"".join(heights[(height - 1 - row) * width:(height - row) * width].tobytes() for row in range(height))


def check_depth_images(run_dir: Path) -> dict[str, list[bytes]]:
    """Checks the depth images of run_dir/run.mcap against the run; returns the raw messages of
    scene/DepthImage and foxglove/depth_image (file order) for byte comparisons."""
    raw: dict[str, list[bytes]] = {IMAGE_TOPIC: [], FOXGLOVE_TOPIC: []}
    images = {}  # step -> (t_ns, side, heights: a side x side float32 array, row-major)
    grids = []  # (t_ns, size, heights)
    run_start = None
    with open(run_dir / "run.mcap", "rb") as f:
        for schema, channel, message in make_reader(f).iter_messages(
                topics=[IMAGE_TOPIC, GRID_TOPIC, FOXGLOVE_TOPIC, "clock/RunStart"], log_time_order=False):
            if channel.topic == "clock/RunStart":
                run_start = climbsim_idl.RunStart.deserialize(message.data)
                continue
            if channel.topic == FOXGLOVE_TOPIC:
                assert schema.name == "foxglove::Grid", schema.name
                raw[FOXGLOVE_TOPIC].append(bytes(message.data))
                continue
            if channel.topic == GRID_TOPIC:
                g = climbsim_idl.DepthGrid.deserialize(message.data)
                grids.append((g.t_ns, g.size, list(g.height_m)))
                continue
            raw[IMAGE_TOPIC].append(bytes(message.data))
            image = climbsim_idl.DepthImage.deserialize(message.data)
            assert message.log_time == image.t_ns == message.publish_time, (message.log_time, image.t_ns)
            assert (image.tile_row0, image.tile_col0, image.tile_rows, image.tile_cols) == (
                0, 0, image.height_px, image.width_px), "a whole image"
            assert not image.mask_runs
            assert image.width_px == image.height_px, "the shipped cameras are square"
            assert len(image.height_m) == image.width_px * image.height_px, len(image.height_m)
            assert image.step not in images, f"frame of step {image.step} recorded twice"
            images[image.step] = (image.t_ns, image.width_px, array("f", image.height_m))
    assert run_start is not None, "no clock/RunStart"
    expected = expected_frame_steps(run_dir, run_start)
    assert sorted(images) == expected, (
        f"{len(images)} frames at steps {sorted(images)[:5]}...; expected {len(expected)} at {expected[:5]}...")
    for step, (t_ns, _, _) in images.items():
        assert t_ns == step * run_start.dt_ns, (step, t_ns)
    assert len(raw[FOXGLOVE_TOPIC]) == len(images), (len(raw[FOXGLOVE_TOPIC]), len(images))
    # The foxglove.Grid of each frame holds its heights, rows from the image's last row up.
    for data, step in zip(raw[FOXGLOVE_TOPIC], sorted(images)):
        _, side, heights = images[step]
        assert flipped_rows(heights, side, side) in data, f"foxglove/depth_image of step {step}"

    # The image the scene rendered: the scene reduced the very frame it rendered at the grid's
    # time to the grid (block means), so the recorded frame's block means are the grid's cells.
    by_time = {t_ns: (side, heights) for t_ns, side, heights in images.values()}
    compared = 0
    for t_ns, size, cells in grids:
        if t_ns not in by_time:
            continue  # a grid of a frame after the recorder's last read
        side, heights = by_time[t_ns]
        worst = max(abs(a - b) for a, b in zip(block_means(heights, side, size), cells))
        assert worst <= 1e-7, f"frame at {t_ns} ns: block means differ from scene/DepthGrid by {worst} m"
        compared += 1
    assert compared >= len(grids) - 1 and compared > 0, (compared, len(grids))
    spread = max(max(h) - min(h) for _, _, h in images.values())
    assert spread > 1e-4, f"every frame is flat ({spread} m)"
    return raw
