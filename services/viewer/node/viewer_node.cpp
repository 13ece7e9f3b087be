#include "viewer_node.hpp"

#include <spdlog/spdlog.h>

#include <set>

#include "clockPubSubTypes.h"
#include "climbsim/topic_names.hpp"
#include "recordPubSubTypes.h"
#include "robotPubSubTypes.h"
#include "scenePubSubTypes.h"
#include "sealingPubSubTypes.h"
#include "thermoPubSubTypes.h"
#include "viewer_translate.hpp"

namespace climbsim::viewer {

namespace {
/// Decodes one recorded sample (CDR as its producer serialised it); false if it does not.
template <class PubSubT>
bool decode(const std::vector<std::uint8_t>& cdr, typename PubSubT::type& sample) {
  eprosima::fastrtps::rtps::SerializedPayload_t payload(static_cast<std::uint32_t>(cdr.size()));
  std::copy(cdr.begin(), cdr.end(), payload.data);
  payload.length = static_cast<std::uint32_t>(cdr.size());
  PubSubT type;
  return type.deserialize(&payload, &sample);
}

template <class PubSubT>
std::unique_ptr<Reader<PubSubT>> directReader(DdsContext& dds, Notifier& n, const std::set<std::string>& recorded,
                                              const char* topic) {
  return recorded.count(topic) != 0 ? nullptr : std::make_unique<Reader<PubSubT>>(dds, topic, qos::kObserver, n);
}
}  // namespace

/// The data readers, created only once the run is under way (RunStart and the first SimTime:
/// the clock grants the first horizon only when every roster member has armed). A producer
/// arms when its writers have matched the readers of the very participants the roster names
/// as its consumers and recorders (by identity), so a reader of ours does not take one's
/// place; created after the start, ours also adds no matching to it.
///
/// What a recorder on the roster records comes from its record batches (one delivery per
/// producer per acknowledgement instead of one per topic per step, best effort, latest batch
/// per producer); only what nobody records is read from the topic itself (best effort,
/// KEEP_LAST 1). The depth comes as the scene's reduced DepthGrid when it is recorded, else
/// from the 256 KiB DepthImage (unless --no-depth).
struct ViewerNode::DataReaders {
  DataReaders(DdsContext& dds, Notifier& n, bool read_depth, const std::set<std::string>& recorded)
      : batches(recorded.empty() ? nullptr
                                 : std::make_unique<Reader<RecordBatchPubSubType>>(dds, topic::kObserverBatch,
                                                                                   qos::kRecordObserver, n)),
        force(directReader<AdhesionForcePubSubType>(dds, n, recorded, topic::kAdhesionForce)),
        chambers(directReader<ChamberStatePubSubType>(dds, n, recorded, topic::kChamberState)),
        pose(directReader<RobotStatePubSubType>(dds, n, recorded, topic::kRobotState)),
        drive(directReader<DriveStatePubSubType>(dds, n, recorded, topic::kDriveState)),
        leakage(directReader<LeakagePubSubType>(dds, n, recorded, topic::kLeakage)),
        depth(read_depth && recorded.count(topic::kDepthGrid) == 0
                  ? std::make_unique<Reader<DepthImagePubSubType>>(dds, topic::kDepthImage, qos::kObserver, n)
                  : nullptr) {}

  std::unique_ptr<Reader<RecordBatchPubSubType>> batches;
  std::unique_ptr<Reader<AdhesionForcePubSubType>> force;
  std::unique_ptr<Reader<ChamberStatePubSubType>> chambers;
  std::unique_ptr<Reader<RobotStatePubSubType>> pose;
  std::unique_ptr<Reader<DriveStatePubSubType>> drive;
  std::unique_ptr<Reader<LeakagePubSubType>> leakage;
  std::unique_ptr<Reader<DepthImagePubSubType>> depth;
};

struct ViewerNode::Readers {
  Readers(DdsContext& dds, Notifier& n)
      : sealing_image(dds, topic::kSealingImage, qos::kObserver, n),
        sealing_picture(dds, topic::kSealingPicture, qos::kObserver, n),
        sim_time(dds, topic::kSimTime, qos::kObserver, n),
        run_start(dds, topic::kRunStart, qos::kLatched, n),
        stop(dds, topic::kStop, qos::kLatched, n),
        ready(dds, topic::kParticipantReady, qos::kLatched, n),
        control(dds, topic::kClockControl, qos::kControl, n) {}

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

bool ViewerNode::readsRecordBatches() const { return data_readers_ && data_readers_->batches; }

void ViewerNode::takeBatches(LiveState& state, PollResult& result) {
  for (const auto& received : data_readers_->batches->take()) {
    const auto& batch = received.data;
    if (!run_id_ || batch.run_id() != *run_id_) continue;
    for (const auto& [topic_name, sample] : latestPerTopic(batch)) {
      const auto& cdr = sample->cdr();
      bool ok = true;
      if (topic_name == topic::kAdhesionForce) {
        AdhesionForce s;
        if ((ok = decode<AdhesionForcePubSubType>(cdr, s))) result.changed |= state.offer(forceFromIdl(s));
      } else if (topic_name == topic::kChamberState) {
        ChamberState s;
        if ((ok = decode<ChamberStatePubSubType>(cdr, s))) result.changed |= state.offer(chambersFromIdl(s));
      } else if (topic_name == topic::kRobotState) {
        RobotState s;
        if ((ok = decode<RobotStatePubSubType>(cdr, s))) result.changed |= state.offer(poseFromIdl(s));
      } else if (topic_name == topic::kDriveState) {
        DriveState s;
        if ((ok = decode<DriveStatePubSubType>(cdr, s))) result.changed |= state.offer(wheelsFromIdl(s));
      } else if (topic_name == topic::kLeakage) {
        Leakage s;
        if ((ok = decode<LeakagePubSubType>(cdr, s))) result.changed |= state.offer(leakFromIdl(s));
      } else if (topic_name == topic::kDepthGrid && read_depth_) {
        DepthGrid s;
        if ((ok = decode<DepthGridPubSubType>(cdr, s))) {
          if (auto grid = gridFromIdl(s); grid && (!result.depth || s.step() >= result.depth_step)) {
            result.depth = std::move(*grid);
            result.depth_step = s.step();
            result.depth_t_ns = s.t_ns();
          } else if (!grid) {
            ok = false;
          }
        }
      }
      if (!ok) spdlog::warn("record batch of '{}': a sample of '{}' dropped (it does not decode)", batch.source().c_str(), topic_name);
    }
  }
  if (result.depth) {
    ++state.depth_version;
    result.changed = true;
  }
}

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
    if (!run_id_) {
      run_id_ = s.data.run_id();
      recorded_ = recordedTopics(s.data);
    }
  }
  for (const auto& s : r.sim_time.take()) {
    applySimTime(state.run, s.data);
    result.changed = true;
    sim_time_seen_ = true;
  }
  for (const auto& s : r.stop.take()) {
    applyStop(state.run, s.data);
    result.changed = true;
  }
  for (auto* reader : {&r.sealing_image, &r.sealing_picture}) {
    for (auto& s : reader->take()) {
      const std::string kind = s.data.kind().to_string();
      result.sealing_png[kind].assign(s.data.png().begin(), s.data.png().end());
      ++state.sealing_versions[kind];
      result.changed = true;
    }
  }
  if (!data_readers_ && run_id_ && sim_time_seen_) {
    data_readers_ = std::make_unique<DataReaders>(dds_, notifier_, read_depth_, recorded_);
    spdlog::info("the run is under way: the step data recorded on its roster ({}) come from record batches, "
                 "the rest from the topics",
                 recorded_.empty() ? std::string("none") : joinedTopics(recorded_));
  }
  if (!data_readers_) return result;
  auto& d = *data_readers_;
  if (d.batches) takeBatches(state, result);
  if (d.force) for (const auto& s : d.force->take()) result.changed |= state.offer(forceFromIdl(s.data));
  if (d.chambers) for (const auto& s : d.chambers->take()) result.changed |= state.offer(chambersFromIdl(s.data));
  if (d.pose) for (const auto& s : d.pose->take()) result.changed |= state.offer(poseFromIdl(s.data));
  if (d.drive) for (const auto& s : d.drive->take()) result.changed |= state.offer(wheelsFromIdl(s.data));
  if (d.leakage) for (const auto& s : d.leakage->take()) result.changed |= state.offer(leakFromIdl(s.data));
  auto depth = d.depth ? d.depth->take() : std::vector<Received<DepthImage>>{};
  // A shard's tile (`climbsim-scene --tile`) is not the image under the robot: only whole images are shown.
  const auto whole = [](const DepthImage& image) {
    return image.mask_runs().empty() && image.tile_row0() == 0 && image.tile_col0() == 0 &&
           (image.tile_rows() == 0 || image.tile_rows() == image.height_px()) &&
           (image.tile_cols() == 0 || image.tile_cols() == image.width_px());
  };
  while (!depth.empty() && !whole(depth.back().data)) depth.pop_back();
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
