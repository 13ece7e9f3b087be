#pragma once
/// @file
/// climbsim-recorder on the lockstep: a roster member that writes the run directory (a part of
/// the executable, not of climbsim_recorder_node, which has no DDS entity).

#include <string>
#include <vector>

#include "climbsim/lockstep_participant.hpp"
#include "recorder/configure.hpp"

namespace climbsim::recorder {

/// Where and what climbsim-recorder writes besides the trace.
struct RunDirectory {
  std::string out_dir;                 ///< --out
  std::string scenario_file;           ///< --scenario ("" for none): copied as out_dir/scenario.yaml
  std::vector<std::string> overrides;  ///< --set: noted at the end of that copy
  bool depth_grids = false;            ///< --depth-grids: scene/DepthGrid into viewer/depth_grids.jsonl
  std::string robot_file;              ///< the robot file read (named in run.mcap's metadata)
  bool mcap = true;                    ///< false (--no-mcap): no run.mcap (what recording costs, tests/bench/e2e)
};

/// Joins the run as `options` says and writes `dir`: scenario.yaml (a copy of the scenario
/// unless it is that file), trace.csv (a row every step of what setup.inputs names, flushed
/// within 20 ms, 40 ms when it follows run.mcap's thread, and at the end), the sealing pictures of setup.picture_times as they arrive
/// (pictures/, waiting up to 5 s at the end for those on their way), the depth grids, and at
/// the end summary.json (climbsim/run_summary/) with the outcome of the clock's Stop, and
/// run.mcap with every sample read, the clock's RunStart and Stop (node/run_recording.hpp); with
/// setup.inputs.depth_images it reads scene/DepthImage at every step, as a consumer on the
/// roster, and records every image into run.mcap (not without run.mcap). Returns
/// the run's exit code.
int runRecorderParticipant(const ParticipantOptions& options, const RunDirectory& dir, RecorderSetup& setup);

}  // namespace climbsim::recorder
