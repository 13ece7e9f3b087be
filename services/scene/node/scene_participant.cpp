#include "scene_participant.hpp"

#include <spdlog/spdlog.h>

#include <optional>
#include <stdexcept>

#include "climbsim/leave_after_results.hpp"
#include "climbsim/height_grid.hpp"
#include "climbsim/run_stats.hpp"
#include "climbsim/topic_names.hpp"
#include "robotPubSubTypes.h"
#include "scenePubSubTypes.h"
#include "scene_translate.hpp"

namespace climbsim::scene {

int runSceneParticipant(const ParticipantOptions& options, const SceneSetup& setup, bool tiled, SceneNode& node) {
  ParticipantOptions sized = options;
  if (setup.write_depth) sized.dds.largest_sample_bytes = imageSampleBytes(node.camera().width_px, node.camera().height_px);
  LockstepParticipant participant(sized);
  auto& robot_state = participant.input<RobotStatePubSubType>(topic::kRobotState);
  auto* depth = setup.write_depth ? &participant.output<DepthImagePubSubType>(topic::kDepthImage) : nullptr;
  auto* laser = setup.write_laser ? &participant.output<LaserScanPubSubType>(topic::kLaserScan) : nullptr;
  // Only a renderer of the whole image can reduce it (a tile renderer has a part of it).
  auto* grid =
      setup.write_depth && !tiled ? &participant.output<DepthGridPubSubType>(climbsim::topic::kDepthGrid) : nullptr;
  DepthGridSchedule grids;

  const int code = participant.run([&](const StepContext& ctx) {
    node.applyRobotStates(robot_state.get(ctx));
    if (depth) {
      std::optional<StatsTimer> render("depth_render_s");
      auto image = node.renderDepthAt(ctx.t_ns);
      render.reset();
      StatsCpuTimer publish("depth_publish_cpu_s");
      // The reduced grid first (it reads the pixels), then the pixels move into the sample
      // (no copy of the image); written in the same order as ever: image, then grid.
      std::optional<climbsim::DepthGrid> reduced;
      if (grid && participant.isRecorded(climbsim::topic::kDepthGrid)) {
        try {
          reduced = grids.offer(image, ctx.t_ns);
        } catch (const std::invalid_argument& e) {  // e.g. a camera that is not square: no grids
          spdlog::warn("scene: no depth grid for replays: {}", e.what());
          grid = nullptr;
        }
      }
      auto sample = depthImageToIdl(std::move(image));
      depth->write(ctx, sample);
      if (reduced) grid->write(ctx, *reduced);
    }
    if (laser) {
      auto sample = laserScanToIdl(node.scanLaser(), node.scannerPoseInWall());
      laser->write(ctx, sample);
    }
  });
  logDroppedSamples(node.droppedRobotStates(), "RobotState samples");
  leaveAfterResults(participant.name().c_str(), code);
  return code;
}

}  // namespace climbsim::scene
