#pragma once
/// @file
/// Debug images of a depth image (OpenCV), for the run directory and for looking at walls.
///
/// 16-bit PNG (one grey channel): u = round((h - far) / (near - far) * 65535), so
///   h = far + u * (near - far) / 65535      [m]
/// (1.5 µm per count for the defaults; 0 is far, i.e. also "nothing seen"; 65535 is near).
/// Colour PNG: the same range [far, near] mapped to 0..255 through an OpenCV colormap
/// (TURBO by default: blue = low/deep, red = high).

#include <cstdint>
#include <string>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "depth_camera.hpp"

namespace climbsim::scene {

/// CV_16UC1 image of the 16-bit encoding above.
cv::Mat depthTo16bit(const DepthImage& image);
/// Height [m] of a 16-bit count (inverse of depthTo16bit up to rounding: <= (near - far) / 131070).
double heightFrom16bit(std::uint16_t count, double near_m, double far_m);
/// CV_8UC3 (BGR) image: the height over [far, near] through `colormap` (cv::ColormapTypes).
cv::Mat depthToColour(const DepthImage& image, int colormap = cv::COLORMAP_TURBO);

/// Write the 16-bit PNG / the colour PNG; throw climbsim::ConfigError naming the path when the
/// file cannot be written.
void writeDepthPng16(const DepthImage& image, const std::string& path);
void writeDepthPngColour(const DepthImage& image, const std::string& path, int colormap = cv::COLORMAP_TURBO);

}  // namespace climbsim::scene
