#include "node/run_recording.hpp"

#include <fastdds/rtps/common/SerializedPayload.h>

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "climbsim/topic_names.hpp"
#include "foxglove_schemasPubSubTypes.h"
#include "node/foxglove_scene.hpp"
#include "clockPubSubTypes.h"
#include "robotPubSubTypes.h"
#include "scenePubSubTypes.h"
#include "sealingPubSubTypes.h"
#include "thermoPubSubTypes.h"

namespace climbsim::recorder {
namespace {

template <class PubSubT>
std::vector<std::uint8_t> serialised(const typename PubSubT::type& sample) {
  // One type support per thread: constructing one computes the type's largest size, which is
  // costly for types with unbounded sequences (the Foxglove ones).
  thread_local PubSubT type;
  auto* data = const_cast<typename PubSubT::type*>(&sample);  // serialize() takes void*, reads only
  eprosima::fastrtps::rtps::SerializedPayload_t payload(type.getSerializedSizeProvider(data)());
  if (!type.serialize(data, &payload)) {
    throw std::runtime_error(std::string("recording: a sample of ") + type.getName() + " does not serialise");
  }
  return {payload.data, payload.data + payload.length};
}

/// {file, text} of a file named in the metadata (text "" if it cannot be read).
std::map<std::string, std::string> fileRecord(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  if (in) text << in.rdbuf();
  return {{"file", path}, {"text", text.str()}};
}

}  // namespace

std::vector<std::uint8_t> cdrBytes(const climbsim::ChamberState& s) { return serialised<ChamberStatePubSubType>(s); }
std::vector<std::uint8_t> cdrBytes(const climbsim::AdhesionForce& s) { return serialised<AdhesionForcePubSubType>(s); }
std::vector<std::uint8_t> cdrBytes(const climbsim::Leakage& s) { return serialised<LeakagePubSubType>(s); }
std::vector<std::uint8_t> cdrBytes(const climbsim::RobotState& s) { return serialised<RobotStatePubSubType>(s); }
std::vector<std::uint8_t> cdrBytes(const climbsim::DriveState& s) { return serialised<DriveStatePubSubType>(s); }
std::vector<std::uint8_t> cdrBytes(const climbsim::DepthGrid& s) { return serialised<DepthGridPubSubType>(s); }
std::vector<std::uint8_t> cdrBytes(const climbsim::DepthImage& s) { return serialised<DepthImagePubSubType>(s); }
std::vector<std::uint8_t> cdrBytes(const climbsim::RunStart& s) { return serialised<RunStartPubSubType>(s); }
std::vector<std::uint8_t> cdrBytes(const climbsim::Stop& s) { return serialised<StopPubSubType>(s); }
std::vector<std::uint8_t> cdrBytes(const climbsim::ValveCommand& s) { return serialised<ValveCommandPubSubType>(s); }
std::vector<std::uint8_t> cdrBytes(const climbsim::EngineCommand& s) { return serialised<EngineCommandPubSubType>(s); }
std::vector<std::uint8_t> cdrBytes(const climbsim::DriveCommand& s) { return serialised<DriveCommandPubSubType>(s); }

RunRecording::RunRecording(const std::string& path, const RecordedInputs& inputs, bool depth_grids,
                           const RecordingFiles& files, const RobotGeometry* geometry)
    : file_(path), geometry_(geometry) {
  const auto add = [this](const char* topic, const char* type) { channels_[topic] = file_.addCdrChannel(topic, type); };
  add(topic::kRunStart, "climbsim::RunStart");
  add(topic::kStop, "climbsim::Stop");
  if (inputs.chamber) add(topic::kChamberState, "climbsim::ChamberState");
  if (inputs.adhesion) add(topic::kAdhesionForce, "climbsim::AdhesionForce");
  if (inputs.leakage) add(topic::kLeakage, "climbsim::Leakage");
  if (inputs.robot) add(topic::kRobotState, "climbsim::RobotState");
  if (inputs.drive) add(topic::kDriveState, "climbsim::DriveState");
  if (inputs.commands) {
    add(topic::kValveCommand, "climbsim::ValveCommand");
    add(topic::kEngineCommand, "climbsim::EngineCommand");
    add(topic::kDriveCommand, "climbsim::DriveCommand");
  }
  if (depth_grids) add(topic::kDepthGrid, "climbsim::DepthGrid");
  if (inputs.depth_images) add(topic::kDepthImage, "climbsim::DepthImage");
  if (geometry_ != nullptr) {
    chamber_shapes_ = chamberShapes(*geometry_);
    add(kFoxgloveTransforms, "foxglove::FrameTransforms");
    add(kFoxgloveScene, "foxglove::SceneUpdate");
    if (depth_grids) add(kFoxgloveDepthGrid, "foxglove::Grid");
    if (inputs.depth_images) add(kFoxgloveDepthImage, "foxglove::Grid");
  }
  file_.metadata("run", {{"runner", files.runner}});
  if (!files.scenario.empty()) file_.metadata("scenario", fileRecord(files.scenario));
  if (!files.robot.empty()) file_.metadata("robot", fileRecord(files.robot));
  if (!files.compose.empty()) file_.metadata("compose", fileRecord(files.compose));
}

RunRecording::~RunRecording() = default;

void RunRecording::offer(std::uint16_t channel, const std::string& source, std::int64_t t_ns,
                         std::vector<std::uint8_t> bytes) {
  auto& last = last_[{channel, source}];
  if (last == bytes) return;
  file_.write(channel, t_ns, bytes.data(), bytes.size());
  last = std::move(bytes);
}

template <class Sample>
void RunRecording::offerAll(std::uint16_t channel, const std::vector<Sample>& samples) {
  for (const auto& s : samples) offer(channel, s.source().to_string(), s.t_ns(), cdrBytes(s));
}

void RunRecording::runStart(const climbsim::RunStart& start) {
  const auto bytes = cdrBytes(start);
  file_.write(channels_.at(topic::kRunStart), 0, bytes.data(), bytes.size());
}

void RunRecording::update(std::int64_t t_ns, const std::vector<climbsim::ChamberState>& states,
                          const std::vector<climbsim::AdhesionForce>& forces,
                          const std::vector<climbsim::Leakage>& leakage,
                          const std::vector<climbsim::RobotState>& poses,
                          const std::vector<climbsim::DriveState>& drives) {
  if (t_ns >= next_chunk_close_ns_) {
    file_.closeChunk();
    next_chunk_close_ns_ = (t_ns / kChunkPeriodNs + 1) * kChunkPeriodNs;
  }
  const auto channel = [this](const char* topic) { return channels_.count(topic) ? channels_.at(topic) : 0; };
  if (const auto c = channel(topic::kChamberState)) offerAll(c, states);
  if (const auto c = channel(topic::kAdhesionForce)) offerAll(c, forces);
  if (const auto c = channel(topic::kLeakage)) offerAll(c, leakage);
  if (const auto c = channel(topic::kRobotState)) offerAll(c, poses);
  if (const auto c = channel(topic::kDriveState)) offerAll(c, drives);
  if (!states.empty() && !ambient_pa_ && !states.back().pressure_pa().empty()) {
    ambient_pa_ = states.back().pressure_pa()[0];
  }
  if (geometry_ == nullptr) return;
  if (t_ns >= next_view_ns_ && !poses.empty()) {
    next_view_ns_ = (t_ns / kViewPeriodNs + 1) * kViewPeriodNs;
    const auto bytes = serialised<foxglove::FrameTransformsPubSubType>(robotTransform(poses.back(), t_ns));
    file_.write(channels_.at(kFoxgloveTransforms), t_ns, bytes.data(), bytes.size());
  }
  if (t_ns < next_scene_ns_) return;
  next_scene_ns_ = (t_ns / kScenePeriodNs + 1) * kScenePeriodNs;
  const auto* state = states.empty() ? nullptr : &states.back();
  const auto* drive = drives.empty() ? nullptr : &drives.back();
  const auto* force = forces.empty() ? nullptr : &forces.back();
  const auto scene = robotScene(*geometry_, chamber_shapes_, state, ambient_pa_.value_or(0.0), drive, force, t_ns);
  const auto bytes = serialised<foxglove::SceneUpdatePubSubType>(scene);
  file_.write(channels_.at(kFoxgloveScene), t_ns, bytes.data(), bytes.size());
}

void RunRecording::commands(const std::vector<climbsim::ValveCommand>& valves,
                            const std::vector<climbsim::EngineCommand>& engines,
                            const std::vector<climbsim::DriveCommand>& drives) {
  offerAll(channels_.at(topic::kValveCommand), valves);
  offerAll(channels_.at(topic::kEngineCommand), engines);
  offerAll(channels_.at(topic::kDriveCommand), drives);
}

void RunRecording::depthGrid(const climbsim::DepthGrid& grid) {
  const auto bytes = cdrBytes(grid);
  file_.write(channels_.at(topic::kDepthGrid), grid.t_ns(), bytes.data(), bytes.size());
  if (const auto found = channels_.find(kFoxgloveDepthGrid); found != channels_.end()) {
    const auto view = serialised<foxglove::GridPubSubType>(depthGridMessage(grid));
    file_.write(found->second, grid.t_ns(), view.data(), view.size());
  }
}

void RunRecording::depthImages(const std::vector<climbsim::DepthImage>& images) {
  for (const auto& image : images) {
    const std::string source = image.source().to_string();
    const auto last = image_steps_.find(source);
    if (last != image_steps_.end() && last->second == image.step()) continue;  // held: written already
    image_steps_[source] = image.step();
    const auto bytes = cdrBytes(image);
    file_.write(channels_.at(topic::kDepthImage), image.t_ns(), bytes.data(), bytes.size());
    const auto found = channels_.find(kFoxgloveDepthImage);
    const bool whole = image.tile_row0() == 0 && image.tile_col0() == 0 && image.tile_rows() == image.height_px() &&
                       image.tile_cols() == image.width_px() && image.mask_runs().empty();
    if (found != channels_.end() && whole) {
      const auto view = serialised<foxglove::GridPubSubType>(depthImageMessage(image));
      file_.write(found->second, image.t_ns(), view.data(), view.size());
    }
  }
}

void RunRecording::stop(const climbsim::Stop& stop) {
  const auto bytes = cdrBytes(stop);
  file_.write(channels_.at(topic::kStop), stop.t_ns(), bytes.data(), bytes.size());
}

void RunRecording::finish(const nlohmann::json& summary) {
  file_.metadata("summary", {{"summary.json", summary.dump(2)}});
  file_.close();
}

}  // namespace climbsim::recorder
