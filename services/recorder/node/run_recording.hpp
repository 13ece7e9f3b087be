#pragma once
/// @file
/// RUN_DIR/run.mcap (docs/recordings.md#what-runmcap-holds): every sample the recorder reads,
/// once, as a DDS reader receives it (CDR with its encapsulation header), on one channel per
/// topic, with the clock's RunStart and Stop and the run's files as metadata. The recorder and
/// `climbsim solo` both write it through this class, from the samples of each step, so the
/// same run gives the same messages.

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "climbsim/recording/mcap_run_file.hpp"
#include "climbsim/robot/robot_geometry.hpp"
#include "clock.h"
#include "foxglove_schemas.h"
#include "configure.hpp"
#include "robot.h"
#include "scene.h"
#include "sealing.h"
#include "thermo.h"

namespace climbsim::recorder {

/// The longest stretch of simulated time whose messages stay in an open chunk [ns]: a
/// recording cut short (a killed recorder) loses at most this much.
inline constexpr std::int64_t kChunkPeriodNs = 1'000'000'000;
/// Period of the Foxglove channels' robot transform [ns] (50 Hz: the robot moves smoothly).
inline constexpr std::int64_t kViewPeriodNs = 20'000'000;
/// Period of the Foxglove robot scene [ns] (10 Hz: suction colours and load arrows; the scene
/// is frame-locked to the robot, so that it moves with every transform).
inline constexpr std::int64_t kScenePeriodNs = 100'000'000;

/// The Foxglove channels (docs/recordings.md#foxglove-channels).
inline constexpr const char* kFoxgloveTransforms = "foxglove/transforms";
inline constexpr const char* kFoxgloveScene = "foxglove/robot";
inline constexpr const char* kFoxgloveDepthGrid = "foxglove/depth_grid";
inline constexpr const char* kFoxgloveDepthImage = "foxglove/depth_image";

/// The files a recording names in its metadata ("" for none).
struct RecordingFiles {
  std::string scenario;  ///< the scenario the services read (RUN_DIR/scenario.yaml)
  std::string robot;     ///< the robot file
  std::string compose;   ///< the compose file of the run ("" for solo: the default composition in one process)
  std::string runner;    ///< "launcher", "recorder" (started on its own) or "solo"
};

class RunRecording {
 public:
  /// Creates `path` with a channel per topic of `inputs` (scene/DepthImage with
  /// inputs.depth_images), clock/RunStart and clock/Stop, and scene/DepthGrid if `depth_grids`;
  /// writes the metadata of `files` (each file's name and text). With `geometry` (the robot's),
  /// also the Foxglove channels: the robot's transform every kViewPeriodNs and scene every
  /// kScenePeriodNs, (with depth_grids) the depth grids as foxglove.Grid and (with
  /// inputs.depth_images) the depth images as foxglove.Grid.
  /// ConfigError if the file cannot be written.
  RunRecording(const std::string& path, const RecordedInputs& inputs, bool depth_grids, const RecordingFiles& files,
               const RobotGeometry* geometry = nullptr);
  ~RunRecording();

  /// The clock's RunStart, at t = 0.
  void runStart(const climbsim::RunStart& start);

  /// The samples the recorder read for the row of time `t_ns` (one per producer, as
  /// TraceRecorder::update takes them): each sample is written the first time it is read,
  /// at its own t_ns (a held sample read again is not). Closes the chunk under way first
  /// when t_ns reaches the next whole period of kChunkPeriodNs. The Foxglove transform of the
  /// samples of this row is written at t_ns when it reaches the next kViewPeriodNs, the scene
  /// when it reaches the next kScenePeriodNs.
  void update(std::int64_t t_ns, const std::vector<climbsim::ChamberState>& states,
              const std::vector<climbsim::AdhesionForce>& forces, const std::vector<climbsim::Leakage>& leakage,
              const std::vector<climbsim::RobotState>& poses, const std::vector<climbsim::DriveState>& drives);

  /// The controller's commands read for the row of t_ns, each once (nothing without inputs.commands).
  void commands(const std::vector<climbsim::ValveCommand>& valves, const std::vector<climbsim::EngineCommand>& engines,
                const std::vector<climbsim::DriveCommand>& drives);

  /// A reduced depth grid (scene/DepthGrid), at its t_ns, and as a foxglove.Grid.
  void depthGrid(const climbsim::DepthGrid& grid);

  /// The depth images read for the row of time t_ns (one per producer, as StampedInput::get
  /// gives them; with inputs.depth_images): each is written the first time it is read, at its
  /// own t_ns, on scene/DepthImage, and a whole image (not a tile) also as a foxglove.Grid on
  /// kFoxgloveDepthImage. A held image read again is not written again.
  void depthImages(const std::vector<climbsim::DepthImage>& images);

  /// The clock's Stop, at its t_ns.
  void stop(const climbsim::Stop& stop);

  /// Writes summary.json's content as the metadata record "summary" and closes the file
  /// (summary section and footer).
  void finish(const nlohmann::json& summary);

 private:
  /// The last sample of `source` written on `channel` (its CDR bytes; empty before the first).
  std::vector<std::uint8_t>& lastBytes(std::uint16_t channel, const char* source);
  /// Writes each sample's CDR bytes on `channel` at its t_ns unless they equal the last sample
  /// of its source there (a held sample read again).
  template <class Sample>
  void offerAll(std::uint16_t channel, const std::vector<Sample>& samples);
  /// Writes the CDR bytes of `sample` on `channel` at t_ns.
  template <class Sample>
  void writeSample(std::uint16_t channel, std::int64_t t_ns, const Sample& sample);

  /// The last bytes written of a source on a channel (a handful: searched in order).
  struct LastSample {
    std::uint16_t channel;
    std::string source;
    std::vector<std::uint8_t> bytes;
  };

  /// The channels written at every step, looked up once (0: not recorded).
  struct StepChannels {
    std::uint16_t chamber = 0, adhesion = 0, leakage = 0, robot = 0, drive = 0;
    std::uint16_t valve_command = 0, engine_command = 0, drive_command = 0;
  };

  recording::McapRunFile file_;
  std::map<std::string, std::uint16_t> channels_;  ///< by topic
  StepChannels step_;
  std::vector<LastSample> last_;
  std::vector<std::uint8_t> scratch_;  ///< the sample being written (its buffer is reused)
  std::map<std::string, std::uint64_t> image_steps_;  ///< by source: the step of the last depth image written
  std::int64_t next_chunk_close_ns_ = kChunkPeriodNs;
  const RobotGeometry* geometry_;
  std::vector<foxglove::TriangleListPrimitive> chamber_shapes_;  ///< chamberShapes(*geometry_)
  std::optional<double> ambient_pa_;  ///< the first ChamberState's (the initial state: ambient)
  std::int64_t next_view_ns_ = 0;
  std::int64_t next_scene_ns_ = 0;
};

}  // namespace climbsim::recorder
