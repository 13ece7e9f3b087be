#pragma once
/// @file
/// The recorder without DDS entities: holds the latest sample of every recorded topic (zero-order
/// hold, as the lockstep delivers them), formats one trace.csv row per step with the columns of
/// docs/scenario-files.md, and accumulates summary.json.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "climbsim/leakage_merger.hpp"
#include "robot.h"
#include "sealing.h"
#include "thermo.h"

namespace climbsim::recorder {

/// The trace's header: t_s, downforce_n, pf_x_m, pf_y_m, p1_pa..pN_pa for the robot's N chambers
/// (the default robot: 7), with a reservoir pr_pa and valve1..valveN,
/// leak_area_m2_<segment> per segment, x_m, y_m, z_m, roll_rad, pitch_rad, yaw_rad,
/// wheel<i>_normal_n, wheel<i>_slip_mps per wheel, downforce_setpoint_n (the set-point the
/// controller that commands the valves published, held by thermo; 0: none stated); all SI.
/// The set-point is last so that the columns before it keep their places.
std::vector<std::string> traceColumns(const std::vector<std::string>& segment_names, int wheel_count,
                                      int chamber_count = 7, bool has_reservoir = true);

/// Roll, pitch, yaw [rad] of a unit quaternion (w, x, y, z), Z-Y-X convention:
/// R = Rz(yaw) Ry(pitch) Rx(roll); pitch in [-pi/2, pi/2].
std::array<double, 3> rollPitchYaw(const std::array<double, 4>& wxyz);

/// Default slide limit [m]: a robot that slides farther than this over a run has lost its grip,
/// a failure of the adhesion controller even if it never fell (the scenario's `slide_limit_m`).
inline constexpr double kDefaultSlideLimitM = 0.005;
/// Slip speed below which a wheel creeps rather than slides [m/s]: rolling with traction needs
/// some slip (bristle model: F |omega| r_w / (k_t sigma), about 1 mm/s at the default robot's
/// 5 cm/s), which is not a loss of grip.
inline constexpr double kSlideSpeedThresholdMps = 0.005;
/// Share of a sealing segment's strip over nothing (Leakage no_surface_share) from which the
/// summary names it under seal_over_nothing, as the sealing's warning does
/// (SealingNode::kNoSurfaceWarnShare).
inline constexpr double kSealOverNothingShare = 0.1;

class TraceRecorder {
 public:
  /// `segment_names` in geometry order (the leak columns), `basic_leak_area_m2` their values
  /// until the first Leakage arrives; `wheel_count` wheel columns; p1..pN for `chamber_count`
  /// chambers, with a reservoir pr and valve1..valveN.
  TraceRecorder(std::vector<std::string> segment_names, std::vector<double> basic_leak_area_m2, int wheel_count,
                int chamber_count = 7, bool has_reservoir = true);

  /// Takes the samples of one step (one per producer); a sample with a non-finite value or the
  /// wrong number of wheels is logged, counted and dropped, the last valid one held.
  void update(const std::vector<climbsim::ChamberState>& states, const std::vector<climbsim::AdhesionForce>& forces,
              const std::vector<climbsim::Leakage>& leakage, const std::vector<climbsim::RobotState>& poses,
              const std::vector<climbsim::DriveState>& drives);

  /// The row of clock time t_ns: every value with "%.17g" (bit-exact round trip), so the same
  /// run gives the same bytes. With setEndOnFall(true) the trace ends at the fall: the first row
  /// that would hold it and every later one are "" (summary's fell_at_s still takes its time).
  std::string row(std::int64_t t_ns);

  /// The scenario's end_on.fall: the trace ends where the run's outcome is decided, whatever
  /// horizon a distributed clock had granted when the fall reached it (rows past the fall would
  /// depend on that timing; solo stops at the same row).
  void setEndOnFall(bool end_on_fall) { end_on_fall_ = end_on_fall; }
  /// True once the trace has ended at the fall (rows are "" from then on).
  bool endedAtFall() const { return end_on_fall_ && fell_; }
  const std::vector<std::string>& columns() const { return columns_; }

  /// summary.json: sim_s, steps, fell, fell_at_s (time of the first row holding the fall, null
  /// if none; the plots mark it), dropped_samples, the downforce after the start hold:
  ///  - downforce_from_s: the hold's end (setDownforceFrom; 0 without a hold);
  ///  - min_downforce_n, mean_downforce_n [N]: the smallest and the mean F of the rows with
  ///    t >= downforce_from_s (null if there are none): while the robot is held the vacuum
  ///    builds from ambient (F = 0 in row 0), which says nothing about the adhesion;
  ///  - max_pf_shift_m: the largest |P_F| (distance from the robot centre) of those rows;
  ///  - downforce_setpoint_n: the controller's published set-point of the last row that had one
  ///    (null if no controller stated one: the plots then fall back to the scenario's);
  ///  - seal_over_nothing: null, or {first_at_s, segments, max_share}: the first row at which a
  ///    segment's strip was at least kSealOverNothingShare over nothing (past the edge of the
  ///    scene, or a hole deeper than the camera's far limit: an open gap), every segment so
  ///    named, and the largest share seen;
  /// and the slide of the robot:
  ///  - max_slip_mps: the largest wheel slip speed of any row;
  ///  - slide_m: sum over rows of v_slide dt, where the robot's slide speed v_slide is the
  ///    smallest slip speed of the wheels in contact (the chassis slides only when every wheel
  ///    does; one wheel scrubbing while the others grip is no slide), counted where it is above
  ///    kSlideSpeedThresholdMps (creep is not a slide), dt the time since the previous row;
  ///  - slide_limit_m, slid (slide_m > slide_limit_m), adhesion_failed (fell or slid).
  /// The caller adds wall_s, realtime_factor and how the run ended.
  nlohmann::json summary() const;

  /// The slide over which a run counts as a failure [m], finite and > 0 (ConfigError otherwise).
  void setSlideLimit(double slide_limit_m);
  /// The clock time from which rows count for min/mean_downforce_n and max_pf_shift_m [ns]:
  /// the end of the scenario's start hold (round(start.hold_s * 1e9)), >= 0.
  void setDownforceFrom(std::int64_t t_ns);

  /// Counts a sample dropped outside update() (a malformed one of another recorded topic).
  void countDropped() { ++dropped_; }
  std::uint64_t droppedSamples() const { return dropped_ + leakage_.dropped(); }

 private:
  std::vector<std::string> columns_;
  LeakageMerger leakage_;
  int wheel_count_;
  std::size_t pressures_;  ///< N chambers, and the reservoir if any
  std::size_t valves_;     ///< N with a reservoir, else 0
  std::optional<climbsim::ChamberState> state_;
  std::optional<climbsim::AdhesionForce> force_;
  std::optional<climbsim::RobotState> pose_;
  std::optional<climbsim::DriveState> drive_;
  std::uint64_t rows_ = 0;
  std::int64_t last_t_ns_ = 0;
  std::int64_t downforce_from_ns_ = 0;
  std::optional<double> min_downforce_n_;
  double sum_downforce_n_ = 0.0;
  std::uint64_t downforce_rows_ = 0;
  double max_pf_shift_m_ = 0.0;
  std::optional<double> setpoint_n_;            ///< last published set-point (> 0)
  bool over_nothing_pending_ = false;           ///< a Leakage over nothing since the last row
  std::optional<std::int64_t> over_nothing_at_ns_;
  std::vector<std::string> over_nothing_segments_;
  double over_nothing_max_share_ = 0.0;
  double max_slip_mps_ = 0.0;
  double slide_m_ = 0.0;
  double slide_limit_m_ = kDefaultSlideLimitM;
  bool fell_ = false;
  bool end_on_fall_ = false;  ///< setEndOnFall
  std::optional<std::int64_t> fell_at_ns_;  ///< clock time of the first row that holds the fall
  std::uint64_t dropped_ = 0;
};

}  // namespace climbsim::recorder
