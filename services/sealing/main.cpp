/// climbsim-sealing: the sealing and leakage service (DESIGN.md §3.2).
///
/// Lockstep mode: reads scene/DepthImage, writes sealing/Leakage (this shard's segments,
/// stamped) every due step and, with --images N, best-effort sealing/SealingImage pictures
/// every N-th due step. With --scenario, shard 0 also publishes the pictures of the first due
/// step at or after each time of the scenario's pictures.sealing_at_s on the reliable
/// sealing/SealingPicture (QoS climbsim.pictures), which the recorder writes into the run
/// directory; they change no number of the run.
/// Offline mode (--offline DEPTH --out DIR): one depth file in, leakage.json and two PNGs out
/// (offline_run.hpp); no DDS.
/// With --scenario (either mode) the robot description comes from the scenario file.

#include <CLI/CLI.hpp>
#include <optional>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <memory>
#include <utility>
#include <vector>

#include "climbsim/errors.hpp"
#include "climbsim/lockstep_participant.hpp"
#include "climbsim/run_stats.hpp"
#include "climbsim/logging.hpp"
#include "climbsim/main_guard.hpp"
#include "climbsim/robot/robot_description.hpp"
#include "climbsim/robot/robot_geometry.hpp"
#include "climbsim/scenario.hpp"
#include "node/picture_schedule.hpp"
#include "node/sealing_node.hpp"
#include "node/sealing_translate.hpp"
#include "offline_run.hpp"
#include "scenePubSubTypes.h"
#include "sealingPubSubTypes.h"
#include "climbsim/shard_tiles/sealing_params.hpp"

#ifndef CLIMBSIM_DEFAULT_ROBOT_FILE
#error "CLIMBSIM_DEFAULT_ROBOT_FILE must name the default robot description"
#endif

int main(int argc, char** argv) {
  using namespace climbsim;
  using namespace climbsim::sealing;
  CLI::App app{"climbsim-sealing: sealing adaptation and leakage per sealing segment"};
  ParticipantOptions options;
  std::string robot_file = CLIMBSIM_DEFAULT_ROBOT_FILE;
  std::string shard_text = "0/1";
  std::vector<std::string> depth_from;
  int camera_px = 256;
  double view_m = 0.80;
  unsigned images_every = 0;
  OfflineOptions offline;
  double scale = 0.0;
  std::string scenario_file;
  std::vector<std::string> overrides;
  options.addOptions(app);
  // Offline runs have no roster; lockstep runs still need --name (checked when the participant starts).
  app.get_option("--name")->required(false);
  auto* scenario_opt = app.add_option("--scenario", scenario_file,
                                      "scenario file (deploy/scenarios/*.yaml): the robot comes from it; excludes --robot");
  app.add_option("--set", overrides, "override a scenario key, e.g. --set robot=FILE (repeatable)")->needs(scenario_opt);
  app.add_option("--robot", robot_file, "robot description (deploy/robots/*.yaml)")->excludes(scenario_opt);
  app.add_option("--shard", shard_text,
                 "compute and publish shard I of N (I/N): a contiguous run of segments by angle, about 1/N of the "
                 "sealing pixels");
  app.add_option("--depth-from", depth_from,
                 "read scene/DepthImage from these producers only (roster names, e.g. scene-1 for the renderer of "
                 "this shard's tile); the others' images are filtered at their writers and never sent here")
      ->delimiter(',');
  app.add_option("--camera-px", camera_px, "depth camera width = height in pixels (lockstep mode; default: the scenario's depth_camera.size_px, else 256)")
      ->check(CLI::Range(1, 1024));
  app.add_option("--view-m", view_m, "width of the depth image on the wall [m]; pixel size = view / width");
  app.add_option("--images", images_every, "publish sealing/SealingImage every N-th due step (0: never)");
  auto* offline_opt = app.add_option("--offline", offline.depth_file,
                                     "offline: depth image (.tif float32 m, .png 16 bit with --scale, .npy float32 m)");
  app.add_option("--out", offline.out_dir, "offline: output directory (leakage.json, edges.png, gaps.png)")
      ->needs(offline_opt);
  auto* scale_opt =
      app.add_option("--scale", scale, "offline, 16-bit PNG: metres per count (height = offset + scale * count)")
          ->needs(offline_opt);
  // Not --offset: that is the participant's schedule offset.
  app.add_option("--height-offset-m", offline.file.offset_m, "offline, 16-bit PNG: height of count 0 [m]")
      ->needs(scale_opt);
  return guardedMain(app, argc, argv, "sealing", [&]() -> int {
    std::vector<double> picture_times;
    bool end_on_seal_over_nothing = false;  ///< the scenario's end_on.seal_over_nothing
    if (!scenario_file.empty()) {
      const Scenario scenario = loadScenario(scenario_file, overrides);
      end_on_seal_over_nothing = scenario.end_on.seal_over_nothing;
      robot_file = scenario.robotPath();
      picture_times = scenario.pictures.sealing_at_s;
      if (scenario.depth_camera.size_px > 0 && app.count("--camera-px") == 0) camera_px = scenario.depth_camera.size_px;
    }
    if (!offline.depth_file.empty()) {
      if (offline.out_dir.empty()) throw ConfigError("--offline needs --out DIR");
      offline.robot_file = robot_file;
      offline.file.view_m = view_m;
      if (*scale_opt) offline.file.scale_m_per_count = scale;
      runOffline(offline);
      return kExitOk;
    }
    initLogging(options.name);
    if (!(view_m > 0.0)) throw ConfigError("--view-m = " + std::to_string(view_m) + ": must be > 0");
    const ShardSpec shard = ShardSpec::parse(shard_text);
    const RobotDescription robot = loadRobotDescription(robot_file);
    const RobotGeometry geometry = computeGeometry(robot);
    const PixelGrid camera{camera_px, camera_px, view_m / camera_px};
    const SealingModel model(sealingParamsFromRobot(robot, geometry), geometry, camera, robot_file);
    SealingNode node(model, shard);
    spdlog::info("sealing: shard {}/{}: {} of {} segments, {} sealing pixels on {}x{} px of {:.6g} m", shard.index,
                 shard.count, node.segments().size(), model.segmentCount(), model.masks().sealingPixels().size(),
                 camera_px, camera_px, camera.pixel_size_m);

    LockstepParticipant participant(options);
    auto& depth = participant.input<DepthImagePubSubType>(topic::kDepthImage, InputLag::kOneStep, depth_from);
    auto& leakage = participant.output<LeakagePubSubType>(topic::kLeakage);
    std::unique_ptr<Writer<SealingImagePubSubType>> images;
    if (images_every > 0) {
      images = std::make_unique<Writer<SealingImagePubSubType>>(participant.dds(), topic::kSealingImage,
                                                                qos::kObserver, participant.notifier());
    }
    // Shard 0 keeps the pictures; with shards each adapting its own region, pixels outside
    // shard 0's region are not computed there (drawn as tight).
    PictureSchedule picture_schedule(shard.index == 0 ? picture_times : std::vector<double>{});
    std::unique_ptr<Writer<SealingImagePubSubType>> kept;
    if (!picture_schedule.empty()) {
      kept = std::make_unique<Writer<SealingImagePubSubType>>(participant.dds(), topic::kSealingPicture,
                                                              qos::kPictures, participant.notifier());
    }
    std::uint64_t due = 0;
    const int code = participant.run([&](const StepContext& ctx) {
      std::optional<StatsCpuTimer> receive("depth_receive_cpu_s");
      auto depth_images = depth.get(ctx);
      receive.reset();
      std::optional<StatsTimer> model("sealing_model_s");
      auto sample = node.step(std::move(depth_images));
      model.reset();
      statsAdd("sealing_adapted_px", static_cast<double>(node.lastAdaptedPixels()));
      leakage.write(ctx, sample);
      if (end_on_seal_over_nothing && !node.noSurfaceWarned().empty()) {
        // The scenario ends a run on it: this step's leakage is written, then the run fails.
        throw std::runtime_error(node.sealOverNothingReason(ctx.t_ns));
      }
      // Encoding the pictures costs; nobody looks without a viewer (an observer) matched.
      if (images && due++ % images_every == 0 && images->matchedReaders() > 0) {
        for (const auto& [kind, png] : node.pictures()) {
          auto picture = sealingImageToIdl(participant.name(), ctx.step, ctx.t_ns, kind, png);
          images->write(picture);
        }
      }
      if (kept && picture_schedule.due(ctx.t_ns)) {
        const auto pictures = node.pictures();  // empty until a valid depth image came: try next step
        for (const auto& [kind, png] : pictures) {
          auto picture = sealingImageToIdl(participant.name(), ctx.step, ctx.t_ns, kind, png);
          kept->write(picture);
        }
        if (!pictures.empty()) picture_schedule.served(ctx.t_ns);
      }
    });
    if (kept && kept->matchedReaders() > 0 && !kept->waitAcknowledged(std::chrono::seconds(5))) {
      spdlog::warn("sealing: the pictures were not all acknowledged within 5 s");
    }
    if (kept && picture_schedule.pending() > 0) {
      spdlog::info("sealing: {} requested picture times after the last computed step", picture_schedule.pending());
    }
    logDroppedSamples(node.dropped(), "depth images; " + std::to_string(node.computed()) + " computed");
    return code;
  });
}
