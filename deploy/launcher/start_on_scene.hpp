#pragma once
/// @file
/// The launcher's check that a scenario's start pose stands on its scene: a robot whose wheels
/// or sealing strips already hang past the edge of the scene (or over a hole deeper than the
/// depth camera reaches) at the start is refused before anything starts, with one line naming
/// the scenario file, the start key and its value (exit code 2).

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "climbsim/robot/robot_geometry.hpp"
#include "climbsim/wall/wall_coverage.hpp"

namespace climbsim::launcher {

/// Share of a segment's strip over nothing from which the start is refused: the share from
/// which the sealing service names a segment during a run (sealing_node.hpp).
inline constexpr double kStartOverNothingShare = 0.10;

/// What of a robot at a pose has no wall under it.
struct OffScene {
  std::vector<int> wheels;  ///< 1-based, in the robot file's wheel order
  /// Segments with at least kStartOverNothingShare of their strip's centre line over nothing,
  /// with that share (0..1), in geometry order.
  std::vector<std::pair<std::string, double>> segments;
  bool beyond_x = false;  ///< some such point lies left or right of the covered box
  bool beyond_y = false;  ///< some such point lies below or above it
  bool any() const { return !wheels.empty() || !segments.empty(); }
};

/// The wheels' contact points and the strips' centre lines (sampled every 5 mm) of a robot whose
/// frame R is at (x_m, y_m) in the wall frame, turned by yaw_rad about the wall's z.
OffScene offSceneAt(const scene::WallCoverage& coverage, const RobotGeometry& geometry, double x_m, double y_m,
                    double yaw_rad);

/// "file:line" of a dotted scenario key ("start.x_m") in `scenario_file`, or "file (--set k=v)"
/// when one of `overrides` sets it; "file" alone if neither finds it.
std::string scenarioKeyWhere(const std::string& scenario_file, const std::vector<std::string>& overrides,
                             const std::string& key);

/// The one-line message for a start pose that is off the scene (nothing if `off` is empty):
/// "<where>: start.x_m = 3.8: the robot would start hanging off the scene: ...". `values` are
/// the start keys' values; `key_where` says where each key is (scenarioKeyWhere).
std::optional<std::string> startOffSceneMessage(const OffScene& off, const scene::WallCoverage& coverage,
                                                double x_m, double y_m, double yaw_deg,
                                                const std::function<std::string(const std::string&)>& key_where,
                                                const std::string& scene_file);

}  // namespace climbsim::launcher
