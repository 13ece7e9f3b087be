#pragma once
/// @file
/// What one step of the sealing service costs (climbsim-bench-sealing's `sealing_step_ms`):
/// SealingNode::step on crack-descent-like depth images, as the service and climbsim solo call
/// it once per depth frame (check the sample, take its pixels, adapt, leakage of every segment,
/// the Leakage sample), against the copy of the frame's heights that hands it the sample.

#include <cstdint>
#include <random>
#include <vector>

#include "climbsim/robot/robot_description.hpp"
#include "climbsim/robot/robot_geometry.hpp"
#include "climbsim/shard_tiles/depth_grid.hpp"
#include "climbsim/shard_tiles/strip_masks.hpp"

namespace climbsim::sealing::bench {

/// Depth images of the robot driving down crack-descent's wall (docs/scenario-files.md): rough
/// concrete (±2 mm on a 12 mm lattice, ±0.2 mm noise per pixel) about 1 mm above the sealing
/// plane, and a straight crack 10 mm wide and 40 mm deep across the robot's x axis that moves
/// `advance_m` along it per frame (1 mm: every frame of the descent at 5 cm/s and 50 depth
/// frames/s), `frames` of them from x = x0_m [m]. The heights of crack-descent's rendered
/// frames have these ranges (-41..+5 mm).
std::vector<DepthGrid> descentFrames(const PixelGrid& grid, int frames, double x0_m, double advance_m,
                                     std::uint64_t seed);

/// Timing of `frames` steps of one SealingNode (every segment) at `px` px with `outline`.
struct StepTiming {
  int px = 0;
  int frames = 0;
  double step_ms = 0.0;        ///< CPU ms per SealingNode::step (its thread's; median of the rounds' means)
  double frame_copy_ms = 0.0;  ///< CPU ms per copy of the frame's DepthImage sample (the same rounds)
  std::size_t sealing_px = 0;  ///< the sealing's pixels
};

/// Times SealingNode::step on descentFrames (`rounds` rounds of `frames` frames, the crack from
/// the lower outer strip to the upper one, after a round to warm up); the copies that hand
/// each step its sample are timed apart. `cold`: 16 MB are written between two steps, as the
/// scene, thermo and drive replace the core's caches between two depth frames of a run; else
/// the steps follow each other with the model's memory in the caches.
StepTiming timeSealingStep(const RobotDescription& robot, const RobotGeometry& geometry, int px, StripOutline outline,
                           int frames, int rounds, bool cold);

}  // namespace climbsim::sealing::bench
