#pragma once
/// @file
/// What the viewer knows of a running simulation: the latest value of every stream it shows
/// (latest value wins: a newer sample replaces an older one, nothing is queued), and the run's
/// state. Pure: no DDS, no wall clock; the node fills it, frameJson() turns it into the JSON
/// the page gets.

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace climbsim::viewer {

/// Where the run is.
enum class RunPhase { kStarting, kRunning, kPaused, kCompleted, kStopped, kFailed };

/// Name of a phase as the page shows it: "starting", "running", "paused", "completed",
/// "stopped", "failed".
const char* phaseName(RunPhase phase);

/// One roster member.
struct RosterMember {
  std::string name;
  std::string host;               ///< host name from its ParticipantReady; empty until seen
  std::uint32_t period_steps = 1;
  std::uint32_t offset_steps = 0;
};

/// The clock's view of the run.
struct RunInfo {
  RunPhase phase = RunPhase::kStarting;
  std::string reason;             ///< why it failed or stopped (Stop.reason), else empty
  std::uint64_t step = 0;         ///< SimTime.step: the step about to be granted
  std::int64_t t_ns = 0;          ///< SimTime.t_ns [ns]
  std::int64_t dt_ns = 0;         ///< RunStart.dt_ns [ns], 0 before RunStart
  std::uint64_t end_step = 0;     ///< RunStart.end_step
  double rtf_target = 0.0;        ///< SimTime.realtime_factor (0: as fast as possible)
  double rtf_measured = 0.0;      ///< simulated / wall time over the last second or so
  std::vector<RosterMember> roster;
  /// Host of each participant that announced itself (ParticipantReady may come before RunStart).
  std::map<std::string, std::string> hosts;
};

/// Simulated over wall time, measured over a sliding window of about one second.
class RateMeter {
 public:
  /// Adds a sample: wall time `wall_ns` (monotonic) at which simulated time was `sim_ns`.
  void add(std::int64_t wall_ns, std::int64_t sim_ns);
  /// Simulated seconds per wall second over the window; 0 until two samples differ in wall time.
  double rate() const { return rate_; }

 private:
  std::int64_t base_wall_ns_ = -1;
  std::int64_t base_sim_ns_ = 0;
  std::int64_t last_wall_ns_ = -1;
  std::int64_t last_sim_ns_ = 0;
  double rate_ = 0.0;
};

/// thermo/AdhesionForce, stamped.
struct ForceValue {
  std::uint64_t step = 0;
  std::int64_t t_ns = 0;
  double downforce_n = 0.0;       ///< F [N]
  double pf_x_m = 0.0;            ///< P_F in the robot frame [m]
  double pf_y_m = 0.0;
  double setpoint_n = 0.0;        ///< the set-point F* of the controller in force [N]; 0: none published
};

/// thermo/ChamberState, stamped.
struct ChamberValue {
  std::uint64_t step = 0;
  std::int64_t t_ns = 0;
  std::vector<double> pressure_pa;      ///< chambers 1..N, then the reservoir if any [Pa]
  std::vector<double> valve_opening;    ///< 0..1, one per chamber with a reservoir, else none
};

/// drive/RobotState, stamped: pose of the robot frame R in the wall frame W.
struct PoseValue {
  std::uint64_t step = 0;
  std::int64_t t_ns = 0;
  std::array<double, 3> position_m{};     ///< origin of R in W [m]
  std::array<double, 4> orientation_wxyz{1, 0, 0, 0};
  bool fell = false;
};

/// drive/DriveState, stamped.
struct WheelsValue {
  std::uint64_t step = 0;
  std::int64_t t_ns = 0;
  std::vector<double> normal_n;           ///< per wheel [N]
  std::vector<double> slip_mps;           ///< per wheel [m/s]
  std::vector<double> steering_rad;       ///< per wheel [rad]
};

/// sealing/Leakage merged over shards: per segment name.
struct LeakValue {
  std::uint64_t step = 0;
  std::int64_t t_ns = 0;
  std::map<std::string, std::pair<double, double>> segments;  ///< name -> (leak area [m²], mean gap [m])
};

/// The latest value of everything the page shows.
struct LiveState {
  RunInfo run;
  std::optional<ForceValue> force;
  std::optional<ChamberValue> chambers;
  std::optional<PoseValue> pose;
  std::optional<WheelsValue> wheels;
  std::optional<LeakValue> leak;
  std::uint64_t depth_version = 0;                 ///< counts depth images taken
  std::map<std::string, std::uint64_t> sealing_versions;  ///< kind ("edges", "gaps") -> count

  /// Replaces `force` if `value` is not older (by step); returns whether it did.
  bool offer(const ForceValue& value);
  bool offer(const ChamberValue& value);
  bool offer(const PoseValue& value);
  bool offer(const WheelsValue& value);
  /// Merges a shard's segments: a newer step starts a new set, the same step adds to it.
  bool offer(const LeakValue& value);
};

/// The stamped streams of one moment: {"force": {...}, "chambers": {...}, "pose": {...},
/// "wheels": {...}} (absent streams left out). The page plots one point per such sample.
nlohmann::json sampleJson(const LiveState& state);

/// The frame sent to the page: {"type": "frame", "run": {...}, "force": {...}, ...}, that is
/// sampleJson() plus the run, the merged leakage and the picture versions; absent streams are
/// left out. Doubles are written with full precision (they read back exactly).
nlohmann::json frameJson(const LiveState& state);

/// The states seen between two messages to the page: the viewer looks at the run up to
/// `--fps` times a second but sends at most `--messages-per-s` messages, each carrying the
/// samples since the previous one (a message costs the browser a wake-up of three of its
/// processes; a sample in it costs almost nothing). At most `capacity` samples are kept (the
/// oldest go first): a page that is not sent to never makes it grow.
class SampleHistory {
 public:
  explicit SampleHistory(std::size_t capacity) : capacity_(capacity) {}
  /// Adds the state's sample (sampleJson) unless it holds the same steps as the last one.
  void add(const LiveState& state);
  /// The samples since the last take(), oldest first; empties the history.
  nlohmann::json take();
  std::size_t size() const { return samples_.size(); }

 private:
  std::size_t capacity_;
  std::vector<nlohmann::json> samples_;
  /// Steps of force, chambers, pose, wheels in the last sample added (-1: absent).
  std::array<std::int64_t, 4> last_steps_{-2, -2, -2, -2};
};

}  // namespace climbsim::viewer
