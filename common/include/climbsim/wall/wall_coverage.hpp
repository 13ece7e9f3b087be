#pragma once
/// @file
/// Where a scene has a wall under a point of the wall plane: what tells a robot hanging past
/// the edge of the scene (or over a hole deeper than the sensors reach) from one on the wall,
/// without rendering (the launcher's start-pose check, the drive's wheel check).
///
/// The wall frame W is the frame the robot's pose is given in: the parent of the part the
/// robot's 3d Pose element moves (x, y in the wall plane, z out of the wall). The static parts'
/// triangles, taken into W, are sampled on a grid of the wall plane: a cell is covered when the
/// line along W's z through the cell's centre meets a triangle at z_W >= -reach_m (a surface no
/// deeper than reach_m below the wall plane, or any above it). A point is covered when its cell
/// is; so an edge is found to within half a cell (cell_m / 2), whatever the triangles' size
/// (the centre of a cell of a contiguous surface always lies in some triangle).

#include <cstdint>
#include <string>
#include <vector>

#include "climbsim/wall/scene.hpp"

namespace climbsim::scene {

class WallCoverage {
 public:
  /// Finest grid step [m]: 5 mm, the size of a few depth pixels.
  static constexpr double kDefaultCell_m = 0.005;
  /// Most cells of a grid; a larger scene gets coarser cells.
  static constexpr std::size_t kMaxCells = 64u << 20;

  /// From triangles already in the wall frame W [m]. reach_m >= 0; cell_m > 0.
  WallCoverage(const TriangleMesh& mesh_W, double reach_m, double cell_m = kDefaultCell_m);

  /// True if the scene has a surface under (x_m, y_m) of the wall plane (see the file comment).
  bool covered(double x_m, double y_m) const;

  bool empty() const { return nx_ == 0 || ny_ == 0; }
  /// The box of the covered cells in W [m] (all 0 when empty()).
  double minX() const { return min_x_; }
  double maxX() const { return max_x_; }
  double minY() const { return min_y_; }
  double maxY() const { return max_y_; }
  double cell() const { return cell_m_; }
  double reach() const { return reach_m_; }

 private:
  double reach_m_ = 0.0;
  double cell_m_ = kDefaultCell_m;
  double x0_ = 0.0, y0_ = 0.0;  ///< lower corner of cell (0, 0)
  std::size_t nx_ = 0, ny_ = 0;
  std::vector<std::uint8_t> covered_;  ///< nx_ * ny_, row-major in y
  double min_x_ = 0.0, max_x_ = 0.0, min_y_ = 0.0, max_y_ = 0.0;
};

/// The part whose frame is the wall frame W of `pose_element` (the parent of the part it moves).
/// ConfigError if there is no such element.
std::size_t wallPartOf(const Scene& scene, const std::string& pose_element);

/// The coverage of `scene`'s static parts in the wall frame of `pose_element`.
WallCoverage wallCoverage(const Scene& scene, const std::string& pose_element, double reach_m,
                          double cell_m = WallCoverage::kDefaultCell_m);

/// How deep under the wall plane a surface still counts [m]: the far limit of the scene's camera
/// `camera` (its depth below the sealing plane) if the scene has it, else 0.05 m (the default
/// depth camera's): what the sealing sees as "nothing" the wheels and the start check do too.
double coverageReach(const SceneDescription& description, const std::string& camera = "depth_cam");

}  // namespace climbsim::scene
