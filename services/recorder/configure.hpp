#pragma once
/// @file
/// climbsim-recorder's configuration (docs/design.md#configuration): the run's scenario, the
/// robot and the command line's own options to the trace's columns and statistics, the
/// summary's label, the topics recorded and the pictures kept. climbsim-recorder's main and
/// climbsim solo both call configureRecorder.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "climbsim/scenario_and_robot.hpp"
#include "node/trace_recorder.hpp"

namespace climbsim::recorder {

/// The topics recorded (an absent one leaves its columns empty). `commands`: the controller's
/// ValveCommand, EngineCommand and DriveCommand, into run.mcap only (a replay's controller under
/// test: docs/recordings.md#replay). `depth_images`: every scene/DepthImage sample, into run.mcap
/// only, read as the sealing reads them (a direct subscription, not record batches: a whole
/// image is larger than a record batch's sample); the scenario's recording.depth_images
/// (docs/recordings.md#full-rate-depth-images).
struct RecordedInputs {
  bool chamber = true, adhesion = true, leakage = true, robot = true, drive = true;
  bool commands = false;
  bool depth_images = false;
};

/// climbsim-recorder's options besides --scenario/--set/--robot/--out.
struct RecorderOverrides {
  std::optional<std::string> label;                    ///< --label: summary.json's scenario (default: the scenario's name)
  std::string inputs = "chamber,adhesion,leakage,robot,drive";  ///< --inputs (or none; "commands" is extra)
};

/// Everything climbsim-recorder records with.
struct RecorderSetup {
  TraceRecorder trace;                ///< the robot's columns; the scenario's slide limit and hold
  std::string label;                  ///< summary.json's scenario
  RecordedInputs inputs;              ///< the topics recorded
  std::vector<double> picture_times;  ///< the scenario's pictures.sealing_at_s [s]
  std::int64_t depth_period_ns = 0;   ///< the scenario's depth period [ns] (0 without a scenario)
  RobotGeometry geometry{};           ///< the robot's: run.mcap's Foxglove scene draws its chambers and wheels
};

/// The recorder setup of `run` and `overrides`. ConfigError for a bad --inputs.
RecorderSetup configureRecorder(const ScenarioAndRobot& run, const RecorderOverrides& overrides = {});

}  // namespace climbsim::recorder
