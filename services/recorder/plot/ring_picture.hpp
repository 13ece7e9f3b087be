#pragma once
/// @file
/// The ring picture of one moment of a run: the chambers of the robot (outlines from
/// RobotGeometry) filled with a colour for their pressure (viridis: dark = deep vacuum,
/// bright = near ambient; light grey: no value) with a colour bar, the wheels as circles whose area is proportional
/// to their normal load, and the point of action P_F of the downforce. Drawn in the wall's
/// orientation: the robot frame is turned by the yaw of that moment, so up in the picture is
/// up on the wall (wall y).

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "climbsim/robot/robot_geometry.hpp"

namespace climbsim::plot {

/// What the picture shows.
struct RingMoment {
  double t_s = 0.0;
  std::vector<double> chamber_pa;       ///< p_1..p_{N+1} [Pa], geometry order (ring chambers, centre)
  double reservoir_pa = 0.0;            ///< p_R [Pa] (in the caption; NaN: no reservoir, no caption line)
  std::vector<double> wheel_normal_n;   ///< normal load per wheel [N], geometry order
  double pf_x_m = 0.0, pf_y_m = 0.0;    ///< P_F in the robot frame [m]
  double downforce_n = 0.0;             ///< F [N] (in the caption)
  double yaw_rad = 0.0;                 ///< rotation of R about the wall normal
};

/// Fixed scales, so that pictures of one run compare.
struct RingScales {
  double p_lo_pa = 80e3;      ///< darkest colour
  double p_hi_pa = 101325.0;  ///< brightest colour, > p_lo_pa
  double load_max_n = 1000.0; ///< wheel load drawn with the largest circle, > 0
};

/// The colour of pressure p [Pa] on the scale (clamped to [p_lo, p_hi]): viridis, whose
/// luminance grows with p.
cv::Vec3b pressureColour(double p_pa, const RingScales& scales);

/// Pixels of the picture: a square ring view of `size_px` plus the colour bar on the right.
struct RingLayout {
  int size_px = 760;      ///< ring view width = height
  double px_per_m = 0.0;  ///< robot drawn so that its body diameter fills about 80 % of the view
  cv::Point2d centre_px;  ///< robot centre
};

RingLayout ringLayout(const RobotGeometry& geometry, double body_diameter_m, int size_px = 760);

/// Pixel of a point given in the robot frame, turned by yaw_rad into the wall's orientation.
cv::Point2d ringPixel(const RingLayout& layout, double yaw_rad, const RobotGeometry::Point& p_Robot);

/// The picture (8-bit BGR), `size_px` + 170 wide, `size_px` high. `body_diameter_m` is
/// drawn as the robot's outer edge.
cv::Mat drawRingPicture(const RobotGeometry& geometry, double body_diameter_m, const RingMoment& moment,
                        const RingScales& scales, int size_px = 760);

}  // namespace climbsim::plot
