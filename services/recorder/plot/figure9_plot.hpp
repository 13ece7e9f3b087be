#pragma once
/// @file
/// The comparison with the original system's figure 9 (a CROMSCI robot crossing a
/// crack): our downforce F and the offset of its point of action |P_F| from a run's
/// trace.csv, over where the crack lies under the robot, side by side with the published
/// numbers, drawn as dashed reference levels (the paper gives levels, not a time series):
/// F from 2200 N down to about 1760 N, P_F about 80 mm off centre.

#include <opencv2/core.hpp>

#include "trace_table.hpp"

namespace climbsim::plot {

/// What the original system's figure 9 shows, as levels.
struct Figure9Reference {
  double downforce_before_n = 2200.0;  ///< set-point, before the crack
  double downforce_on_crack_n = 1760.0;  ///< lowest level while the crack is under the robot
  double pf_offset_m = 0.08;           ///< largest offset of P_F from the centre
};

/// Where a horizontal crack at wall height crack_y_m lies along the robot's x axis, from its
/// centre [m]: (crack_y - y) / sin(yaw), for every row of the trace (NaN where |sin yaw| < 0.5:
/// the crack would not run across the robot's x axis).
std::vector<double> crackOffsetAlongX(const TraceTable& trace, double crack_y_m);

/// Two charts side by side (left F [N], right |P_F| [mm], both over the crack's offset along
/// R's x [m]), with the reference levels dashed, from the rows with t_s >= from_s (leave out
/// the hold while the vacuum builds). Needs t_s, downforce_n, pf_x_m, pf_y_m, y_m, yaw_rad.
cv::Mat figure9Plot(const TraceTable& trace, double crack_y_m, double from_s = 0.0,
                    const Figure9Reference& reference = {});

}  // namespace climbsim::plot
