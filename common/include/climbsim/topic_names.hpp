#pragma once
/// @file
/// The data topics of the closed loop (DESIGN.md §1, §4), in one place for every service and
/// the recorder. Types in idl/*.idl; QoS profiles in deploy/qos/climbsim.xml.

namespace climbsim::topic {

inline constexpr const char* kDriveCommand = "controller/DriveCommand";   ///< DriveCommand
inline constexpr const char* kValveCommand = "controller/ValveCommand";   ///< ValveCommand
inline constexpr const char* kEngineCommand = "controller/EngineCommand"; ///< EngineCommand
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
