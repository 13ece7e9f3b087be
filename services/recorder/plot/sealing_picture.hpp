#pragma once
/// @file
/// The sealing pictures of a run made readable: the raw pictures the sealing service publishes
/// (pictures/sealing_<kind>_<t>s.png: one pixel per depth pixel, in the robot frame) turned
/// wall-up like the ring pictures (by the robot's yaw at that moment), enlarged, with the time,
/// a scale bar, the robot's x axis and a legend of the colours.

#include <string>

#include <opencv2/core.hpp>

namespace climbsim::plot {

/// What is known of one raw sealing picture.
struct SealingPictureInfo {
  std::string kind;            ///< "edges" or "gaps"
  double t_s = 0.0;            ///< time of the picture [s]
  double yaw_rad = 0.0;        ///< robot yaw about the wall normal at that time
  double pixel_size_m = 0.0;   ///< side of one raw pixel on the wall [m], > 0
  double far_m = -0.05;        ///< depth grey scale: black (edges; gaps: the dimmed background)
  double near_m = 0.05;        ///< depth grey scale: white
  double full_scale_gap_m = 0.005;  ///< gaps: white at this gap [m] (the sealing travel)
};

/// The annotated picture (8-bit BGR) of `raw` (8-bit BGR, row 0 at the robot's +y edge,
/// column 0 at its -x edge).
cv::Mat annotateSealingPicture(const cv::Mat& raw, const SealingPictureInfo& info);

}  // namespace climbsim::plot
