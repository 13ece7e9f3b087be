#pragma once
/// @file
/// `climbsim-sealing --offline DEPTH --robot ROBOT --out DIR`: one depth image file through
/// the sealing model, without DDS.
///
/// Writes into DIR (created if missing):
///  - leakage.json: per segment (geometry order) name, length_m, pixels, leak_area_m2,
///    basic_leak_area_m2 (l_i L_basic), mean_gap_m, max_gap_m, over_travel_px; totals
///    total_leak_area_m2, total_basic_leak_area_m2, mean_gap_m (over all sealing pixels),
///    over_travel_px; and the inputs (files, grid, sealing parameters);
///  - edges.png: the depth image (-0.05 m black .. +0.05 m white) with the strips' outlines
///    in red and the borders between segments in yellow;
///  - gaps.png: sealing pixels black (tight) to white (gap >= travel_m), the rest of the depth
///    image dimmed in blue.
/// Both pictures have the depth image's size.

#include <optional>
#include <string>

#include "depth_file.hpp"

namespace climbsim::sealing {

struct OfflineOptions {
  std::string depth_file;
  std::string robot_file;
  std::string out_dir;
  DepthFileOptions file;
};

/// Runs the offline mode; ConfigError "<file>: <problem>" for a bad depth file, robot file,
/// a sealing that does not fit the image, or an output directory that cannot be written.
/// Returns the total leak area [m^2].
double runOffline(const OfflineOptions& options);

}  // namespace climbsim::sealing
