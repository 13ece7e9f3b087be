#pragma once
/// @file
/// Every DDS topic of climbsim in one table: name, type, who writes it, how often and with
/// which QoS profile of deploy/qos/climbsim.xml. `climbsim topics` prints it,
/// docs/design.md#topics-and-qos shows it, and a test checks it against the services' code
/// (tests/unit/common/topic_catalog_test.py).

#include <array>

#include "climbsim/topic_names.hpp"

namespace climbsim {

/// One topic.
struct TopicInfo {
  const char* name;      ///< DDS topic name
  const char* type;      ///< IDL struct (DDS type name climbsim::<type>), idl/*.idl
  const char* producer;  ///< who writes it
  const char* rate;      ///< how often
  const char* qos;       ///< QoS profile in deploy/qos/climbsim.xml
};

/// Every topic, the clock's first.
inline constexpr std::array<TopicInfo, 22> kTopicCatalog = {{
    {topic::kParticipantReady, "ParticipantReady", "every roster member", "once, before step 0", "climbsim.latched"},
    {topic::kRunStart, "RunStart", "clock", "once, when the roster is complete", "climbsim.latched"},
    {topic::kStepGrant, "StepGrant", "clock", "each new horizon (about every W/2 steps)", "climbsim.control"},
    {topic::kStepDone, "StepDone", "every roster member", "progress every W/2 steps and at the horizon", "climbsim.control"},
    {topic::kStop, "Stop", "clock", "once, at the end", "climbsim.latched"},
    {topic::kSimTime, "SimTime", "clock", "each new horizon", "climbsim.observer"},
    {topic::kClockControl, "ClockControl", "climbsim-clockctl, allowed participants", "on request",
     "climbsim.control"},
    {topic::kRecordBatch, "RecordBatch", "producers of recorded topics", "with each acknowledgement of progress",
     "climbsim.record"},
    {topic::kObserverBatch, "RecordBatch", "producers of recorded topics (while an observer is matched)",
     "the newest of each recorded topic, at most 30 a second", "climbsim.record_observer"},
    {topic::kDriveCommand, "DriveCommand", "controller", "every step", "climbsim.step_data"},
    {topic::kValveCommand, "ValveCommand", "controller (external: your client)", "every step",
     "climbsim.step_data"},
    {topic::kEngineCommand, "EngineCommand", "controller", "every step", "climbsim.step_data"},
    {topic::kRobotState, "RobotState", "drive", "the steps a consumer reads (scene: every depth frame)", "climbsim.step_data"},
    {topic::kDriveState, "DriveState", "drive", "the steps a consumer reads (recorder: in record batches)", "climbsim.step_data"},
    {topic::kDepthImage, "DepthImage", "scene", "rates.depth_hz", "climbsim.step_data"},
    {topic::kDepthGrid, "DepthGrid", "scene (when a recorder records it)",
     "every 0.1 s of simulated time, in record batches only", "climbsim.record"},
    {topic::kLaserScan, "LaserScan", "scene (--outputs laser)", "rates.laser_hz", "climbsim.step_data"},
    {topic::kLeakage, "Leakage", "sealing (one part per shard)", "rates.depth_hz", "climbsim.step_data"},
    {topic::kSealingImage, "SealingImage", "sealing (--images N)", "every N-th due step", "climbsim.observer"},
    {topic::kSealingPicture, "SealingImage", "sealing", "at pictures.sealing_at_s", "climbsim.pictures"},
    {topic::kChamberState, "ChamberState", "thermo", "every step", "climbsim.step_data"},
    {topic::kAdhesionForce, "AdhesionForce", "thermo", "every step", "climbsim.step_data"},
}};

}  // namespace climbsim
