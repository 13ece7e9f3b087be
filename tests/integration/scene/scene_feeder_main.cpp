/// climbsim-test-scene-feeder: drives and watches climbsim-scene in the integration tests.
/// Each due step k it writes drive/RobotState with the pose of feederPose(k) (a slow drift and
/// turn on the wall; NaN in position_m at the steps of --nan-at) and, with --record, reads
/// scene/DepthImage and writes every --stride-th pixel of every --stride-th row in hexfloat,
/// one line per image, so that the test checks the heights against the known geometry.

#include <cstdio>
#include <fstream>
#include <limits>
#include <set>

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "climbsim/errors.hpp"
#include "climbsim/lockstep_participant.hpp"
#include "climbsim/logging.hpp"
#include "climbsim/main_guard.hpp"
#include "robotPubSubTypes.h"
#include "scenePubSubTypes.h"
#include "scene_feeder_pose.hpp"
#include "scene_translate.hpp"

int main(int argc, char** argv) {
  using namespace climbsim;
  CLI::App app{"climbsim-test-scene-feeder: feeds RobotState to climbsim-scene and records its depth images"};
  ParticipantOptions options;
  std::string record_file;
  int stride = 1;
  std::vector<std::uint64_t> nan_at;
  options.addOptions(app);
  app.add_option("--record", record_file, "read scene/DepthImage and write it to this file");
  app.add_option("--stride", stride, "record every stride-th row and column (>= 1)");
  app.add_option("--nan-at", nan_at, "steps whose RobotState carries NaN");
  return guardedMain(app, argc, argv, "test-scene-feeder", [&]() -> int {
    initLogging(options.name);
    if (stride < 1) throw ConfigError("--stride = " + std::to_string(stride) + ": must be >= 1");
    const std::set<std::uint64_t> nan_steps(nan_at.begin(), nan_at.end());
    LockstepParticipant participant(options);
    auto& robot_state = participant.output<RobotStatePubSubType>(scene::topic::kRobotState);
    StampedInput<DepthImagePubSubType>* depth = nullptr;
    std::ofstream record;
    if (!record_file.empty()) {
      record.open(record_file, std::ios::trunc);
      if (!record) throw ConfigError("--record = '" + record_file + "': cannot write it");
      depth = &participant.input<DepthImagePubSubType>(scene::topic::kDepthImage);
    }
    const int code = participant.run([&](const StepContext& ctx) {
      if (depth) {
        for (const auto& image : depth->get(ctx)) {
          char buffer[64];
          record << "image " << image.step() << ' ' << image.width_px() << ' ' << image.height_px() << ' ' << stride;
          for (double v : {image.pixel_size_m(), image.near_m(), image.far_m()}) {
            std::snprintf(buffer, sizeof(buffer), " %a", v);
            record << buffer;
          }
          record << ' ' << image.height_m().size();
          for (std::uint32_t row = 0; row < image.height_px(); row += stride) {
            for (std::uint32_t col = 0; col < image.width_px(); col += stride) {
              std::snprintf(buffer, sizeof(buffer), " %a",
                            static_cast<double>(image.height_m()[std::size_t(row) * image.width_px() + col]));
              record << buffer;
            }
          }
          record << '\n';
        }
      }
      auto sample = scene::robotStateToIdl(scene::testing::feederPose(ctx.step));
      if (nan_steps.count(ctx.step)) sample.position_m()[0] = std::numeric_limits<double>::quiet_NaN();
      robot_state.write(ctx, sample);
    });
    record.flush();
    return code;
  });
}
