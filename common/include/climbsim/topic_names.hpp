#pragma once
/// @file
/// Every DDS topic name of climbsim, in one place for every C++ program: the clock's control
/// plane (types in idl/clock.idl), the record batches recorders read (idl/record.idl) and the
/// data topics of the closed loop (docs/design.md#the-loop, docs/design.md#topics-and-qos). QoS
/// profiles in deploy/qos/climbsim.xml. topic_catalog.hpp lists each with its type, producer and
/// rate; the Python and C lists are generated from that table (climbsim-topicgen), and
/// tests/unit/common/topic_catalog_test.py checks that this header, the table, the generated lists and the
/// table of docs/design.md#topics-and-qos agree.

namespace climbsim::topic {

// The clock's control plane and the record batches.
inline constexpr const char* kStepGrant = "clock/StepGrant";              ///< RELIABLE
inline constexpr const char* kStepDone = "clock/StepDone";                ///< RELIABLE, keyed by participant
inline constexpr const char* kParticipantReady = "clock/ParticipantReady";///< TRANSIENT_LOCAL, keyed
inline constexpr const char* kRunStart = "clock/RunStart";                ///< TRANSIENT_LOCAL
inline constexpr const char* kStop = "clock/Stop";                        ///< TRANSIENT_LOCAL
inline constexpr const char* kSimTime = "clock/SimTime";                  ///< BEST_EFFORT
inline constexpr const char* kClockControl = "clock/ClockControl";        ///< RELIABLE
inline constexpr const char* kRecordBatch = "record/RecordBatch";         ///< RELIABLE, KEEP_ALL (idl/record.idl)
/// RecordBatch for observers: the newest sample of each recorded topic, at most 30 a second
inline constexpr const char* kObserverBatch = "record/ObserverBatch";    ///< BEST_EFFORT, KEEP_LAST 1 per producer

// The data topics of the closed loop.
inline constexpr const char* kDriveCommand = "controller/DriveCommand";   ///< DriveCommand
inline constexpr const char* kValveCommand = "controller/ValveCommand";   ///< ValveCommand
inline constexpr const char* kEngineCommand = "controller/EngineCommand"; ///< EngineCommand

/// The commands of the robot: one writer each in a run (two controllers would fight over the
/// valves, engines or wheels); the clock refuses a roster with two writers of one of them.
inline constexpr const char* kSingleWriterTopics[] = {kValveCommand, kEngineCommand, kDriveCommand};
inline constexpr const char* kRobotState = "drive/RobotState";            ///< RobotState
inline constexpr const char* kDriveState = "drive/DriveState";            ///< DriveState
inline constexpr const char* kDepthImage = "scene/DepthImage";            ///< DepthImage
/// DepthGrid: the depth image reduced, only in record batches (recorder, viewer)
inline constexpr const char* kDepthGrid = "scene/DepthGrid";
inline constexpr const char* kLaserScan = "scene/LaserScan";              ///< LaserScan
inline constexpr const char* kLeakage = "sealing/Leakage";                ///< Leakage (parts per shard)
inline constexpr const char* kSealingImage = "sealing/SealingImage";      ///< SealingImage (viewers)
/// SealingImage at the scenario's pictures.sealing_at_s (the recorder keeps them)
inline constexpr const char* kSealingPicture = "sealing/SealingPicture";
inline constexpr const char* kChamberState = "thermo/ChamberState";       ///< ChamberState
inline constexpr const char* kAdhesionForce = "thermo/AdhesionForce";     ///< AdhesionForce

}  // namespace climbsim::topic
