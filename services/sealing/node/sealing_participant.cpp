#include "sealing_participant.hpp"

#include <spdlog/spdlog.h>

#include <chrono>
#include <memory>
#include <optional>
#include <stdexcept>
#include <utility>

#include "climbsim/leave_after_results.hpp"
#include "climbsim/run_stats.hpp"
#include "picture_schedule.hpp"
#include "scenePubSubTypes.h"
#include "sealingPubSubTypes.h"
#include "sealing_translate.hpp"

namespace climbsim::sealing {

int runSealingParticipant(const ParticipantOptions& options, const SealingLockstepOptions& lockstep,
                          const SealingSetup& setup, SealingNode& node) {
  ParticipantOptions sized = options;
  const bool writes_images = lockstep.images_every > 0 || !setup.picture_times.empty();
  // Its images (PNG, at most 4 bytes a pixel) and the pictures in its record batches.
  if (writes_images) sized.dds.largest_sample_bytes = imageSampleBytes(setup.camera.width_px, setup.camera.height_px);
  LockstepParticipant participant(sized);
  auto& depth = participant.input<DepthImagePubSubType>(topic::kDepthImage, InputLag::kOneStep, lockstep.depth_from);
  auto& leakage = participant.output<LeakagePubSubType>(topic::kLeakage);
  std::unique_ptr<Writer<SealingImagePubSubType>> images;
  if (lockstep.images_every > 0) {
    images = std::make_unique<Writer<SealingImagePubSubType>>(participant.dds(), topic::kSealingImage,
                                                              qos::kObserver, participant.notifier());
  }
  // Shard 0 keeps the pictures; with shards each adapting its own region, pixels outside
  // shard 0's region are not computed there (drawn as tight).
  PictureSchedule picture_schedule(setup.picture_times);
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
    if (setup.end_on_seal_over_nothing && !node.noSurfaceWarned().empty()) {
      // The scenario ends a run on it: this step's leakage is written, then the run fails.
      throw std::runtime_error(node.sealOverNothingReason(ctx.t_ns));
    }
    // Encoding the pictures costs; nobody looks without a viewer (an observer) matched.
    if (images && due++ % lockstep.images_every == 0 && images->matchedReaders() > 0) {
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
  leaveAfterResults(participant.name().c_str(), code);
  return code;
}

}  // namespace climbsim::sealing
