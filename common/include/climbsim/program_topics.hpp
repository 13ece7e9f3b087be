#pragma once
/// @file
/// Which topics each climbsim program may write and read: what the launcher grants a
/// participant in the permissions document of a secured run. A program writes a
/// subset of its list depending on its options (scene --outputs, sealing --images, ...); the
/// table holds every topic it can use, nothing else. tests/unit/launcher/security_material_test.cpp checks
/// each name against the topic catalog (climbsim/topic_catalog.hpp).

#include <string>
#include <vector>

#include "climbsim/topic_names.hpp"

namespace climbsim {

/// The topics one program uses.
struct ProgramTopics {
  std::string program;              ///< executable name (argv[0]'s file name)
  std::vector<std::string> writes;  ///< topics it may publish
  std::vector<std::string> reads;   ///< topics it may subscribe to
  bool lockstep = true;             ///< on the clock's roster: also the lockstep topics below
};

/// What every roster participant adds (common/src/lockstep_participant.cpp): it announces
/// itself, reports progress and record batches, and follows the clock.
inline ProgramTopics lockstepTopics() {
  return {"", {topic::kParticipantReady, topic::kStepDone, topic::kRecordBatch, topic::kObserverBatch},
          {topic::kStepGrant, topic::kRunStart, topic::kStop}, false};
}

/// Every program a secured run can start, and the clock's control tool.
inline const std::vector<ProgramTopics>& programTopics() {
  static const std::vector<ProgramTopics> table = {
      {"climbsim-clock",
       {topic::kStepGrant, topic::kRunStart, topic::kStop, topic::kSimTime},
       {topic::kParticipantReady, topic::kStepDone, topic::kClockControl},
       false},
      {"climbsim-clockctl", {topic::kClockControl}, {}, false},
      {"climbsim-scene", {topic::kDepthImage, topic::kDepthGrid, topic::kLaserScan}, {topic::kRobotState}},
      {"climbsim-sealing", {topic::kLeakage, topic::kSealingImage, topic::kSealingPicture}, {topic::kDepthImage}},
      {"climbsim-thermo",
       {topic::kChamberState, topic::kAdhesionForce},
       {topic::kLeakage, topic::kValveCommand, topic::kEngineCommand}},
      {"climbsim-drive", {topic::kRobotState, topic::kDriveState}, {topic::kDriveCommand, topic::kAdhesionForce}},
      {"climbsim-controller",
       {topic::kDriveCommand, topic::kValveCommand, topic::kEngineCommand},
       {topic::kChamberState, topic::kAdhesionForce}},
      {"climbsim-recorder",
       {},
       {topic::kRecordBatch, topic::kAdhesionForce, topic::kChamberState, topic::kDepthGrid, topic::kDriveState,
        topic::kLeakage, topic::kRobotState, topic::kSealingPicture, topic::kValveCommand, topic::kEngineCommand,
        topic::kDriveCommand}},
      {"climbsim-replay",
       {topic::kChamberState, topic::kAdhesionForce, topic::kLeakage, topic::kRobotState, topic::kDriveState},
       {}},
      {"climbsim-viewer",
       {topic::kClockControl},
       {topic::kObserverBatch, topic::kSimTime, topic::kRunStart, topic::kStop, topic::kParticipantReady,
        topic::kAdhesionForce, topic::kChamberState, topic::kRobotState, topic::kDriveState, topic::kLeakage,
        topic::kDepthImage, topic::kDepthGrid, topic::kSealingImage, topic::kSealingPicture},
       false},
  };
  return table;
}

/// The entry of `program` (a file name), or nullptr if the table has none.
inline const ProgramTopics* findProgramTopics(const std::string& program) {
  for (const auto& entry : programTopics()) {
    if (entry.program == program) return &entry;
  }
  return nullptr;
}

}  // namespace climbsim
