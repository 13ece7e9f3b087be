#pragma once
/// @file
/// What a sweep reports of each finished variant (no processes here): read from the variant's
/// run directory (trace.csv, summary.json), written as one row of sweep.csv, and the overlay
/// plots of all variants on shared axes.

#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "sweep_spec.hpp"

namespace climbsim::sweep {

/// The figures of one finished variant.
struct VariantResult {
  Variant variant;
  std::string outcome;            ///< summary.json's outcome (completed, fell, stopped, failed)
  bool fell = false;              ///< summary.json's fell: the robot left the wall
  double min_downforce_n = 0.0;   ///< smallest F over the rows from `from_s` on [N] (NaN: no row)
  double mean_downforce_n = 0.0;  ///< mean F over the same rows [N]
  double max_pf_shift_m = 0.0;    ///< largest |P_F| (distance of P_F from the robot centre) [m]
  double max_slip_mps = 0.0;      ///< largest wheel slip speed of any row [m/s]
  double wall_s = 0.0;            ///< wall time of the variant's process [s]
  // How the run ended, as summary.json says it (docs/scenario-files.md#what-a-run-writes):
  bool slid = false;              ///< slide_m > slide_limit_m: a failure of the adhesion controller
  double slide_m = 0.0;           ///< distance slid with every wheel in contact slipping [m]
  double slide_limit_m = 0.0;     ///< the scenario's slide_limit_m [m]
  bool adhesion_failed = false;   ///< fell or slid
  std::optional<double> fell_at_s;               ///< when the robot left the wall [s]
  std::optional<double> seal_over_nothing_at_s;  ///< first time the seal was over no wall [s]
  std::optional<double> wheels_over_nothing_at_s;  ///< first time a wheel was over no wall [s]
  long long dropped_samples = 0;  ///< samples a service refused
  int exit_code = 0;              ///< the run's exit code
  std::string culprit;            ///< the participant that ended the run ("" for none)
  std::string reason;             ///< the reason the run ended
  std::vector<double> t_s, downforce_n, pf_x_m, pf_y_m;  ///< the curves, for the overlay plots
};

/// Reads `run_dir`/trace.csv and summary.json. The downforce figures and the P_F shift are
/// taken over the rows with t_s >= from_s (the scenario's start.hold_s: while the robot is held
/// the vacuum builds from ambient, F = 0 at first, which says nothing about the variant), and
/// never row 0 (before any thermo sample). ConfigError naming the file if one is missing or
/// malformed.
VariantResult readVariant(const Variant& variant, const std::string& run_dir, double wall_s, double from_s);

/// sweep.csv: a header (variant, one column per swept key, outcome, fell, min_downforce_n,
/// mean_downforce_n, max_pf_shift_m, max_slip_mps, wall_s, dir, then how each run ended as its
/// summary.json says it: slid, slide_m, slide_limit_m, adhesion_failed, fell_at_s,
/// seal_over_nothing_at_s, wheels_over_nothing_at_s, dropped_samples, exit_code, culprit,
/// reason) and a row per result, in variant order. Numbers are printed with %.17g; a time that
/// never came (null in summary.json) is an empty cell.
std::string sweepCsv(const std::vector<SweepAxis>& axes, const std::vector<VariantResult>& results);

/// The mark a variant's legend entry gets after its values: " (fell)", " (slid)" (stayed on
/// the wall, slid beyond the limit), " (failed)" or " (stopped)"; "" for a run that completed
/// within the slide limit.
std::string outcomeMark(const VariantResult& result);

/// F [N] of every variant over time on shared axes; one colour per variant, the legend its
/// values and outcomeMark.
cv::Mat downforceOverlay(const std::vector<SweepAxis>& axes, const std::vector<VariantResult>& results);
/// P_F x and y [mm] (robot frame) of every variant over time, a panel each, as downforceOverlay.
cv::Mat pfOverlay(const std::vector<SweepAxis>& axes, const std::vector<VariantResult>& results);

}  // namespace climbsim::sweep
