"""Topic names of climbsim (common/include/climbsim/clock_topics.hpp, topic_names.hpp)."""

# Clock control plane (idl/clock.idl).
STEP_GRANT = "clock/StepGrant"  #: RELIABLE
STEP_DONE = "clock/StepDone"  #: RELIABLE, keyed by participant
PARTICIPANT_READY = "clock/ParticipantReady"  #: TRANSIENT_LOCAL, keyed by participant
RUN_START = "clock/RunStart"  #: TRANSIENT_LOCAL
STOP = "clock/Stop"  #: TRANSIENT_LOCAL
SIM_TIME = "clock/SimTime"  #: BEST_EFFORT
CLOCK_CONTROL = "clock/ClockControl"  #: RELIABLE

# Data topics of the closed loop (step data: RELIABLE, KEEP_LAST 4, stamped).
DRIVE_COMMAND = "controller/DriveCommand"  #: DriveCommand
VALVE_COMMAND = "controller/ValveCommand"  #: ValveCommand
ENGINE_COMMAND = "controller/EngineCommand"  #: EngineCommand
ROBOT_STATE = "drive/RobotState"  #: RobotState
DRIVE_STATE = "drive/DriveState"  #: DriveState
DEPTH_IMAGE = "scene/DepthImage"  #: DepthImage
LASER_SCAN = "scene/LaserScan"  #: LaserScan
LEAKAGE = "sealing/Leakage"  #: Leakage (parts per shard)
SEALING_IMAGE = "sealing/SealingImage"  #: SealingImage (viewers, observer QoS)
CHAMBER_STATE = "thermo/ChamberState"  #: ChamberState
ADHESION_FORCE = "thermo/AdhesionForce"  #: AdhesionForce
DEPTH_GRID = "scene/DepthGrid"  #: DepthGrid (record batches only)
