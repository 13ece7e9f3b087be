#pragma once
/// @file
/// Translators between the scene service's topics (idl/robot.idl RobotState, idl/scene.idl
/// DepthImage and LaserScan) and the scene and render types. Pure functions: no DDS entity,
/// tested without a network. Stamps (source, step, t_ns) are left to StampedOutput::write.

#include <optional>
#include <string>

#include "climbsim/height_grid.hpp"
#include "climbsim/topic_names.hpp"
#include "depth_frames.hpp"
#include "render_scene.hpp"
#include "robot.h"
#include "scene.h"

namespace climbsim::scene {

/// Topic names: the one list of common/include/climbsim/topic_names.hpp (topic::kLeakage, ...).
namespace topic = climbsim::topic;

/// "" if `state` gives a usable pose of R in W, else a one-line reason naming the field and
/// value: every position and quaternion component finite, quaternion norm within 1e-3 of 1.
std::string checkRobotState(const climbsim::RobotState& state);
/// T_W_R of a checked RobotState: position_m and orientation_wxyz (renormalised).
Pose robotPoseFromIdl(const climbsim::RobotState& state);
/// A RobotState holding T_W_R (velocities zero), for feeders and tests.
climbsim::RobotState robotStateToIdl(const Pose& T_W_R);

/// The IDL image of a rendered one (same layout: row-major, row 0 at +y, column 0 at -x).
/// A masked tile sends only its mask's pixels inside the tile (mask_runs, the mask's row runs;
/// its box's other pixels are never read): a shard of 2's tile of a 1024 px image is 0.44 MB, not
/// its box's 3.3 MB. std::invalid_argument if it is larger than the topic's bound (2048 x 2048).
climbsim::DepthImage depthImageToIdl(const DepthImage& image);
/// The same, moving the pixels into the sample instead of copying them (`image` is left
/// without pixels; for the 3-4 MB images of a 1024 px camera, published every frame).
climbsim::DepthImage depthImageToIdl(DepthImage&& image);
/// The rendered image an IDL sample carries (for consumers and round-trip tests).
/// std::invalid_argument if height_m does not hold width_px * height_px values.
DepthImage depthImageFromIdl(const climbsim::DepthImage& sample);

/// The IDL grid of a reduced depth image (height_grid.hpp; same layout as the image).
/// std::invalid_argument if it has more than 64 x 64 cells (the topic's bound).
climbsim::DepthGrid depthGridToIdl(const HeightGrid& grid);

/// When the scene reduces its depth image for replays (scene/DepthGrid): at the first due step
/// at or after each multiple of kInterval_ns, a function of the step alone, so that the same
/// run gives the same grids (the scene service and solo alike).
class DepthGridSchedule {
 public:
  static constexpr std::int64_t kInterval_ns = WholeDepthFrames::kWholeInterval_ns;  ///< at most every 0.1 s of simulated time
  static constexpr int kCells = 64;                          ///< cells per side, at most

  /// The reduced grid of `image` if one is due at t_ns and the image is whole (then the next one
  /// is due at the next multiple of kInterval_ns), else nothing (a masked frame leaves the grid
  /// due: WholeDepthFrames renders the frames it is due at whole). std::invalid_argument for an image that cannot
  /// be reduced (not square).
  std::optional<climbsim::DepthGrid> offer(const DepthImage& image, std::int64_t t_ns);

 private:
  std::int64_t next_ns_ = 0;
};

/// The IDL scan of a rendered one; the scanner pose is given in the wall frame W (T_W_S).
/// std::invalid_argument if it has more beams than the topic holds (4096).
climbsim::LaserScan laserScanToIdl(const LaserScan& scan, const Pose& T_W_S);

}  // namespace climbsim::scene
