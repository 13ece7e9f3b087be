#pragma once
/// @file
/// Depth images from files, for `climbsim-sealing --offline` (same convention as the
/// DepthImage topic: heights above the sealing plane [m], row 0 at +y, column 0 at -x, the
/// image centre at the robot centre, square pixels).
///
/// Formats, by file extension:
///  - .tif / .tiff: one channel of float32, heights in metres;
///  - .png: one channel of 16 bit, height_m = offset_m + scale_m_per_count * count (scale
///    required; e.g. scale 1.0 / 65535 * 0.1 and offset -0.05 map 0..65535 onto -0.05..+0.05 m);
///  - .npy: a 2-D little-endian float32 array ('<f4', C order), heights in metres.
/// The pixel size is view_m / width.

#include <optional>
#include <string>
#include <vector>

#include "climbsim/shard_tiles/depth_grid.hpp"

namespace climbsim::sealing {

struct DepthFileOptions {
  double view_m = 0.0;  ///< width of the image on the wall [m], > 0 (climbsim-sealing: SealingSetup::view_m)
  std::optional<double> scale_m_per_count;   ///< 16-bit PNG only: metres per count, finite and != 0
  double offset_m = 0.0;                     ///< 16-bit PNG only: height of count 0 [m]
};

/// Reads a depth image. Throws ConfigError "<path>: <problem>" for a missing or unreadable
/// file, an unknown extension, a wrong pixel type or channel count, a malformed .npy header,
/// a PNG without a scale, a scale given for another format, or a non-finite pixel (named by
/// row and column).
DepthGrid readDepthFile(const std::string& path, const DepthFileOptions& options);

/// The .npy reader alone: rows, columns and values of a 2-D '<f4' C-order array in `bytes`.
/// Throws std::invalid_argument with the problem (no file name).
std::vector<float> parseNpyFloat32(const std::string& bytes, int& rows, int& cols);

}  // namespace climbsim::sealing
