#pragma once
/// @file
/// `climbsim-bench-scene --hires`: what a tile renderer of a sealing shard costs
/// against the whole 1024 x 1024 px image on the default pylon (scene_bench_main.cpp's file
/// comment has the output).

#include <string>

namespace climbsim::bench {

/// Renders `frames` frames of crack-descent-hires's descent on `scene_file`, whole and as the
/// tiles of `climbsim-scene --tile I/N` for the robot in `robot_file`; prints the
/// `bench: scene: hires` lines and writes them as JSON to `out_path` (if not empty). With
/// `only_layout` (e.g. "0/2", "0/2-box"), the whole image and that layout alone.
int hiresTiles(const std::string& scene_file, const std::string& robot_file, int frames, const std::string& out_path,
               const std::string& only_layout = "");

}  // namespace climbsim::bench
