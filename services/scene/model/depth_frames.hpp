#pragma once
/// @file
/// Which depth frames are rendered whole and which only at the pixels the sealing reads
/// (docs/design.md#what-the-scene-renders). The sealing reads every frame, but only its strips:
/// the mask of the whole sealing (ShardTiles of shard 0/1, node/shard_tile.hpp). The other
/// readers of the depth image read it whole, at frames fixed by the step's time alone:
///   - the reduced depth grid (DepthGridSchedule, node/scene_translate.hpp): the first frame at
///     or after each multiple of kWholeInterval_ns (0.1 s) of simulated time; the viewer, the
///     replay wall and run.mcap's Foxglove depth grid read it;
///   - the sealing pictures (the scenario's pictures.sealing_at_s): the frame the sealing reads
///     at the first of its steps at or after each requested time (it reads a frame one step
///     after it is rendered);
///   - run.mcap's every depth image (the scenario's recording.depth_images): every frame.
/// The viewer shows only whole images, so it sees the grid's frames.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace climbsim::scene {

/// What decides the whole frames of a run (configureScene fills it from the scenario).
struct DepthFrameChoice {
  /// Mask the frames that are not whole to the pixels the whole sealing of this robot reads
  /// (deploy/robots/*.yaml); "": every frame whole.
  std::string robot_file;
  bool subpixel = false;             ///< the sealing reads sub-pixel strip shares (the scenario's depth_camera.subpixel)
  std::vector<double> read_at_s;     ///< the sealing pictures' times [s]: their frames whole
  std::int64_t read_lag_ns = 0;      ///< the clock's step [ns]: the sealing reads a frame this much later
  bool every_frame_whole = false;    ///< every frame whole (recording.depth_images)
  /// A whole frame every WholeDepthFrames::kWholeInterval_ns for the reduced depth grid (what
  /// replays and the viewer show); false where no grid is kept (an in-process run without
  /// run.mcap): only the pictures' frames are whole then.
  bool depth_grids = true;
  bool masked() const { return !robot_file.empty() && !every_frame_whole; }
};

/// The whole frames of one run, decided frame by frame in the order of the steps (stateful: the
/// grid and the pictures each take the first frame at or after their times).
class WholeDepthFrames {
 public:
  /// Interval of the reduced depth grid [ns] (DepthGridSchedule::kInterval_ns).
  static constexpr std::int64_t kWholeInterval_ns = 100'000'000;

  explicit WholeDepthFrames(const DepthFrameChoice& choice = {});

  /// Whether the frame rendered at t_ns [ns] (read by the sealing at t_ns + read_lag_ns) is
  /// whole; frames must come in order of time. Always true without a mask.
  bool whole(std::int64_t t_ns);

 private:
  bool masked_ = false;
  bool every_frame_ = true;
  bool depth_grids_ = true;
  std::int64_t next_grid_ns_ = 0;
  std::int64_t read_lag_ns_ = 0;
  std::vector<std::int64_t> read_at_ns_;  ///< sorted
  std::size_t next_read_ = 0;
};

}  // namespace climbsim::scene
