#pragma once
/// @file
/// `climbsim-bench-scene --crack-descent`: CPU per depth frame of crack-descent's camera on the
/// default pylon, the renderer's path against the reference path (RenderOptions::
/// reference_raster) on the same poses in the same run, with and without the sub-pixel option
/// (scene_bench_main.cpp's file comment has the output).

#include <string>

namespace climbsim::bench {

/// Renders `frames` depth frames (50 Hz: held 2 s, then down the wall at 5 cm/s) of the
/// scenario `scenario_file` (crack-descent) with the run's camera and scene (configureScene,
/// `build_dir` for "$BUILD/"), by both paths, centre rays only and with area-weighted edge
/// pixels; prints the `bench: scene: crack-descent` lines and writes them as JSON to `out_path`
/// (if not empty). Exit code 1 when a frame of the two paths differs in any bit.
/// `subpixel_only`: only the renderer's frames with area-weighted edge pixels (for a profiler),
/// one line, nothing compared. `masked_only`: only the renderer's frames on the default run's
/// masks (the sealing's pixels; its whole frames left out), for a profiler, one line.
int crackDescentFrames(const std::string& scenario_file, const std::string& build_dir, int frames,
                       const std::string& out_path, bool subpixel_only = false, bool masked_only = false);

}  // namespace climbsim::bench
