/// climbsim-sealing: the sealing and leakage service (docs/design.md#sealing-and-leakage).
///
/// Lockstep mode: reads scene/DepthImage, writes sealing/Leakage (this shard's segments,
/// stamped) every due step and, with --images N, best-effort sealing/SealingImage pictures
/// every N-th due step. With --scenario, shard 0 also publishes the pictures of the first due
/// step at or after each time of the scenario's pictures.sealing_at_s on the reliable
/// sealing/SealingPicture (QoS climbsim.pictures), which the recorder writes into the run
/// directory; they change no number of the run (node/sealing_participant.hpp).
/// Offline mode (--offline DEPTH --out DIR): one depth file in, leakage.json and two PNGs out
/// (offline_run.hpp); no DDS.
/// With --scenario (either mode) the robot description comes from the scenario file (configure.hpp).

#include <spdlog/spdlog.h>

#include "climbsim/errors.hpp"
#include "climbsim/logging.hpp"
#include "climbsim/scenario.hpp"
#include "climbsim/service_command_line.hpp"
#include "configure.hpp"
#include "node/sealing_participant.hpp"
#include "offline_run.hpp"

int main(int argc, char** argv) {
  using namespace climbsim;
  using namespace climbsim::sealing;
  ServiceCommandLine cli("climbsim-sealing: sealing adaptation and leakage per sealing segment",
                         "scenario file (deploy/scenarios/*.yaml): the robot comes from it; excludes --robot",
                         "robot=FILE");
  SealingOverrides o;
  SealingLockstepOptions lockstep;
  OfflineOptions offline;
  double scale = 0.0;
  CLI::App& app = cli.app;
  // Offline runs have no roster; lockstep runs still need --name (checked when the participant starts).
  app.get_option("--name")->required(false);
  cli.addRobotOption();
  app.add_option("--shard", o.shard,
                 "compute and publish shard I of N (I/N): a contiguous run of segments by angle, about 1/N of the "
                 "sealing pixels");
  app.add_option("--depth-from", lockstep.depth_from,
                 "read scene/DepthImage from these producers only (roster names, e.g. scene-1 for the renderer of "
                 "this shard's tile); the others' images are filtered at their writers and never sent here")
      ->delimiter(',');
  app.add_option("--camera-px", o.camera_px, "depth camera width = height in pixels (lockstep mode; default: the scenario's depth_camera.size_px, else 256)")
      ->check(CLI::Range(1, Scenario::DepthCamera::kMaxSizePx));
  app.add_option("--view-m", o.view_m, "width of the depth image on the wall [m]; pixel size = view / width");
  app.add_option("--images", lockstep.images_every, "publish sealing/SealingImage every N-th due step (0: never)");
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
  return cli.run(argc, argv, "sealing", [&]() -> int {
    if (offline.depth_file.empty()) initLogging(cli.participant.name);
    const ScenarioAndRobot run = cli.load();
    const SealingSetup setup = configureSealing(run, o);
    if (!offline.depth_file.empty()) {
      if (offline.out_dir.empty()) throw ConfigError("--offline needs --out DIR");
      offline.robot_file = run.robot_file;
      offline.file.view_m = setup.view_m;
      if (*scale_opt) offline.file.scale_m_per_count = scale;
      runOffline(offline);
      return kExitOk;
    }
    const SealingModel model(setup.params, run.geometry, setup.camera, run.robot_file);
    SealingNode node(model, setup.shard);
    spdlog::info("sealing: shard {}/{}: {} of {} segments, {} sealing pixels on {}x{} px of {:.6g} m", setup.shard.index,
                 setup.shard.count, node.segments().size(), model.segmentCount(), model.masks().sealingPixels().size(),
                 setup.camera.width_px, setup.camera.height_px, setup.camera.pixel_size_m);
    return runSealingParticipant(cli.participant, lockstep, setup, node);
  });
}
