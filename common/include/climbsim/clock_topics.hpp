#pragma once
/// @file
/// Topic names of the clock's control plane (types in idl/clock.idl) and of the record
/// batches that recorders read (idl/record.idl).

namespace climbsim::topics {

inline constexpr const char* kStepGrant = "clock/StepGrant";              ///< RELIABLE
inline constexpr const char* kStepDone = "clock/StepDone";                ///< RELIABLE, keyed by participant
inline constexpr const char* kParticipantReady = "clock/ParticipantReady";///< TRANSIENT_LOCAL, keyed
inline constexpr const char* kRunStart = "clock/RunStart";                ///< TRANSIENT_LOCAL
inline constexpr const char* kStop = "clock/Stop";                        ///< TRANSIENT_LOCAL
inline constexpr const char* kSimTime = "clock/SimTime";                  ///< BEST_EFFORT
inline constexpr const char* kClockControl = "clock/ClockControl";        ///< RELIABLE
inline constexpr const char* kRecordBatch = "record/RecordBatch";         ///< RELIABLE, KEEP_ALL (idl/record.idl)

}  // namespace climbsim::topics
