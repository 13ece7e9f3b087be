#include "viewer_node.hpp"

#include <spdlog/spdlog.h>

#include "clockPubSubTypes.h"
#include "climbsim/clock_topics.hpp"
#include "climbsim/topic_names.hpp"
#include "robotPubSubTypes.h"
#include "scenePubSubTypes.h"
#include "sealingPubSubTypes.h"
#include "thermoPubSubTypes.h"
#include "viewer_translate.hpp"

namespace climbsim::viewer {

/// The step-data readers. Created only once the run is under way (the first SimTime): a
/// producer arms when its writer has matched as many readers as the roster has consumers,
/// so a reader of ours matched before that could stand in for a consumer not matched yet,
/// which would then miss the first samples (VOLATILE) and stall the run.
struct ViewerNode::StepReaders {
  StepReaders(DdsContext& dds, Notifier& n, bool read_depth)
      : force(dds, topic::kAdhesionForce, qos::kObserver, n),
        chambers(dds, topic::kChamberState, qos::kObserver, n),
        pose(dds, topic::kRobotState, qos::kObserver, n),
        drive(dds, topic::kDriveState, qos::kObserver, n),
        leakage(dds, topic::kLeakage, qos::kObserver, n),
        depth(read_depth ? std::make_unique<Reader<DepthImagePubSubType>>(dds, topic::kDepthImage, qos::kObserver, n)
                         : nullptr) {}

  Reader<AdhesionForcePubSubType> force;
  Reader<ChamberStatePubSubType> chambers;
  Reader<RobotStatePubSubType> pose;
  Reader<DriveStatePubSubType> drive;
  Reader<LeakagePubSubType> leakage;
  std::unique_ptr<Reader<DepthImagePubSubType>> depth;
};

struct ViewerNode::Readers {
  Readers(DdsContext& dds, Notifier& n)
      : sealing_image(dds, topic::kSealingImage, qos::kObserver, n),
        sealing_picture(dds, topic::kSealingPicture, qos::kObserver, n),
        sim_time(dds, topics::kSimTime, qos::kObserver, n),
        run_start(dds, topics::kRunStart, qos::kLatched, n),
        stop(dds, topics::kStop, qos::kLatched, n),
        ready(dds, topics::kParticipantReady, qos::kLatched, n),
        control(dds, topics::kClockControl, qos::kControl, n) {}

  Reader<SealingImagePubSubType> sealing_image;
  Reader<SealingImagePubSubType> sealing_picture;
  Reader<SimTimePubSubType> sim_time;
  Reader<RunStartPubSubType> run_start;
  Reader<StopPubSubType> stop;
  Reader<ParticipantReadyPubSubType> ready;
  Writer<ClockControlPubSubType> control;
};

ViewerNode::ViewerNode(const DdsSettings& settings, const std::string& name, int max_depth_cells, bool read_depth)
    : name_(name),
      max_depth_cells_(max_depth_cells),
      dds_(settings, name),
      read_depth_(read_depth),
      readers_(std::make_unique<Readers>(dds_, notifier_)) {}

ViewerNode::~ViewerNode() = default;

PollResult ViewerNode::poll(LiveState& state) {
  PollResult result;
  auto& r = *readers_;
  for (const auto& s : r.ready.take()) {
    applyReady(state.run, s.data);
    result.changed = true;
  }
  for (const auto& s : r.run_start.take()) {
    applyRunStart(state.run, s.data);
    result.changed = true;
  }
  for (const auto& s : r.sim_time.take()) {
    applySimTime(state.run, s.data);
    result.changed = true;
    if (!step_readers_) step_readers_ = std::make_unique<StepReaders>(dds_, notifier_, read_depth_);
  }
  if (!step_readers_) return result;
  auto& d = *step_readers_;
  for (const auto& s : r.stop.take()) {
    applyStop(state.run, s.data);
    result.changed = true;
  }
  for (const auto& s : d.force.take()) result.changed |= state.offer(forceFromIdl(s.data));
  for (const auto& s : d.chambers.take()) result.changed |= state.offer(chambersFromIdl(s.data));
  for (const auto& s : d.pose.take()) result.changed |= state.offer(poseFromIdl(s.data));
  for (const auto& s : d.drive.take()) result.changed |= state.offer(wheelsFromIdl(s.data));
  for (const auto& s : d.leakage.take()) result.changed |= state.offer(leakFromIdl(s.data));
  auto depth = d.depth ? d.depth->take() : std::vector<Received<DepthImage>>{};
  if (!depth.empty()) {
    const auto& image = depth.back().data;
    try {
      result.depth = downsampleHeights(image.height_m(), image.width_px(), image.height_px(), image.pixel_size_m(),
                                       blockFor(image.width_px(), max_depth_cells_));
      result.depth_step = image.step();
      result.depth_t_ns = image.t_ns();
      ++state.depth_version;
      result.changed = true;
    } catch (const std::exception& e) {
      spdlog::warn("depth image of step {} dropped: {}", image.step(), e.what());
    }
  }
  for (auto* reader : {&r.sealing_image, &r.sealing_picture}) {
    for (auto& s : reader->take()) {
      const std::string kind = s.data.kind().to_string();
      result.sealing_png[kind].assign(s.data.png().begin(), s.data.png().end());
      ++state.sealing_versions[kind];
      result.changed = true;
    }
  }
  return result;
}

bool ViewerNode::send(const ClockRequest& request) {
  std::lock_guard<std::mutex> lock(control_mutex_);
  if (readers_->control.matchedReaders() == 0) return false;
  auto sample = controlToIdl(request, name_);
  readers_->control.write(sample);
  return true;
}

}  // namespace climbsim::viewer
