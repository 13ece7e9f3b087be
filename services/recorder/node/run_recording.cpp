#include "node/run_recording.hpp"

#include <cstring>
#include <fstream>
#include <sstream>

#include "climbsim/topic_names.hpp"
#include "node/cdr_encoding.hpp"
#include "node/foxglove_scene.hpp"

namespace climbsim::recorder {
namespace {

/// {file, text} of a file named in the metadata (text "" if it cannot be read).
std::map<std::string, std::string> fileRecord(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  if (in) text << in.rdbuf();
  return {{"file", path}, {"text", text.str()}};
}

}  // namespace


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
  const auto id = [this](const char* topic) -> std::uint16_t {
    const auto found = channels_.find(topic);
    return found == channels_.end() ? 0 : found->second;
  };
  step_ = {id(topic::kChamberState), id(topic::kAdhesionForce), id(topic::kLeakage), id(topic::kRobotState),
           id(topic::kDriveState),   id(topic::kValveCommand),  id(topic::kEngineCommand), id(topic::kDriveCommand)};
  file_.metadata("run", {{"runner", files.runner}});
  if (!files.scenario.empty()) file_.metadata("scenario", fileRecord(files.scenario));
  if (!files.robot.empty()) file_.metadata("robot", fileRecord(files.robot));
  if (!files.compose.empty()) file_.metadata("compose", fileRecord(files.compose));
}

RunRecording::~RunRecording() = default;

std::vector<std::uint8_t>& RunRecording::lastBytes(std::uint16_t channel, const char* source) {
  for (auto& last : last_) {
    if (last.channel == channel && std::strcmp(last.source.c_str(), source) == 0) return last.bytes;
  }
  last_.push_back({channel, source, {}});
  return last_.back().bytes;
}

template <class Sample>
void RunRecording::offerAll(std::uint16_t channel, const std::vector<Sample>& samples) {
  for (const auto& s : samples) {
    encodeCdr(s, scratch_);
    auto& last = lastBytes(channel, s.source().c_str());
    if (last == scratch_) continue;  // held: written already
    file_.write(channel, s.t_ns(), scratch_.data(), scratch_.size());
    last.swap(scratch_);  // the buffers change hands: neither is allocated again
  }
}

template <class Sample>
void RunRecording::writeSample(std::uint16_t channel, std::int64_t t_ns, const Sample& sample) {
  encodeCdr(sample, scratch_);
  file_.write(channel, t_ns, scratch_.data(), scratch_.size());
}

void RunRecording::runStart(const climbsim::RunStart& start) { writeSample(channels_.at(topic::kRunStart), 0, start); }

void RunRecording::update(std::int64_t t_ns, const std::vector<climbsim::ChamberState>& states,
                          const std::vector<climbsim::AdhesionForce>& forces,
                          const std::vector<climbsim::Leakage>& leakage,
                          const std::vector<climbsim::RobotState>& poses,
                          const std::vector<climbsim::DriveState>& drives) {
  if (t_ns >= next_chunk_close_ns_) {
    file_.closeChunk();
    next_chunk_close_ns_ = (t_ns / kChunkPeriodNs + 1) * kChunkPeriodNs;
  }
  if (step_.chamber != 0) offerAll(step_.chamber, states);
  if (step_.adhesion != 0) offerAll(step_.adhesion, forces);
  if (step_.leakage != 0) offerAll(step_.leakage, leakage);
  if (step_.robot != 0) offerAll(step_.robot, poses);
  if (step_.drive != 0) offerAll(step_.drive, drives);
  if (!states.empty() && !ambient_pa_ && !states.back().pressure_pa().empty()) {
    ambient_pa_ = states.back().pressure_pa()[0];
  }
  if (geometry_ == nullptr) return;
  if (t_ns >= next_view_ns_ && !poses.empty()) {
    next_view_ns_ = (t_ns / kViewPeriodNs + 1) * kViewPeriodNs;
    writeSample(channels_.at(kFoxgloveTransforms), t_ns, robotTransform(poses.back(), t_ns));
  }
  if (t_ns < next_scene_ns_) return;
  next_scene_ns_ = (t_ns / kScenePeriodNs + 1) * kScenePeriodNs;
  const auto* state = states.empty() ? nullptr : &states.back();
  const auto* drive = drives.empty() ? nullptr : &drives.back();
  const auto* force = forces.empty() ? nullptr : &forces.back();
  writeSample(channels_.at(kFoxgloveScene), t_ns,
              robotScene(*geometry_, chamber_shapes_, state, ambient_pa_.value_or(0.0), drive, force, t_ns));
}

void RunRecording::commands(const std::vector<climbsim::ValveCommand>& valves,
                            const std::vector<climbsim::EngineCommand>& engines,
                            const std::vector<climbsim::DriveCommand>& drives) {
  if (step_.drive_command == 0) return;  // commands not recorded
  offerAll(step_.valve_command, valves);
  offerAll(step_.engine_command, engines);
  offerAll(step_.drive_command, drives);
}

void RunRecording::depthGrid(const climbsim::DepthGrid& grid) {
  writeSample(channels_.at(topic::kDepthGrid), grid.t_ns(), grid);
  if (const auto found = channels_.find(kFoxgloveDepthGrid); found != channels_.end()) {
    writeSample(found->second, grid.t_ns(), depthGridMessage(grid));
  }
}

void RunRecording::depthImages(const std::vector<climbsim::DepthImage>& images) {
  for (const auto& image : images) {
    const std::string source = image.source().to_string();
    const auto last = image_steps_.find(source);
    if (last != image_steps_.end() && last->second == image.step()) continue;  // held: written already
    image_steps_[source] = image.step();
    writeSample(channels_.at(topic::kDepthImage), image.t_ns(), image);
    const auto found = channels_.find(kFoxgloveDepthImage);
    const bool whole = image.tile_row0() == 0 && image.tile_col0() == 0 && image.tile_rows() == image.height_px() &&
                       image.tile_cols() == image.width_px() && image.mask_runs().empty();
    if (found != channels_.end() && whole) {
      writeSample(found->second, image.t_ns(), depthImageMessage(image));
    }
  }
}

void RunRecording::stop(const climbsim::Stop& stop) {
  writeSample(channels_.at(topic::kStop), stop.t_ns(), stop);
}

void RunRecording::finish(const nlohmann::json& summary) {
  file_.metadata("summary", {{"summary.json", summary.dump(2)}});
  file_.close();
}

}  // namespace climbsim::recorder
