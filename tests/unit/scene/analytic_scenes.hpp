#pragma once
/// @file
/// Test walls whose depth image is known in closed form: piecewise-affine height fields
/// h(x, y) in a wall frame F (solid below h), meshed exactly, and the ray oracle that
/// intersects a camera ray with the analytic surface (not with the mesh).

#include <functional>
#include <vector>

#include "depth_camera.hpp"
#include "climbsim/wall/triangle_mesh.hpp"

namespace climbsim::scene::testing {

/// A height field on [x_lines.front(), x_lines.back()] x [y_lines.front(), y_lines.back()]
/// whose formula is affine inside every cell of the grid of lines (jumps and kinks lie on
/// lines only).
struct AnalyticWall {
  std::function<double(double x, double y)> height_m;  ///< any value at a jump; used inside cells only
  std::vector<double> x_lines;                         ///< sorted, include the domain bounds
  std::vector<double> y_lines;
};

/// Exact mesh of the wall in F: two triangles per cell sharing vertices where h is
/// continuous, and vertical faces along lines where it jumps.
TriangleMesh meshWall(const AnalyticWall& wall, std::uint32_t part_id = 0);

/// Mesh mapped by T (p -> T p) and appended to `into`.
void appendMesh(TriangleMesh& into, const TriangleMesh& mesh, const Pose& T = Pose::Identity());

/// Closed box [lo, hi] (12 triangles) with one part id.
TriangleMesh box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, std::uint32_t part_id);

/// Expected depth of pixel (row, col) of `camera` at T_F_C (camera pose in the wall frame):
/// z_C where the pixel's ray, starting on the near plane, first meets the analytic surface,
/// clamped to far (far also where it meets nothing above far). The wall must lie below the
/// near plane along the ray's start.
double expectedDepth(const AnalyticWall& wall, const Pose& T_F_C, const DepthCameraParams& camera, int row, int col);

/// The same wall with extra lines every `spacing_m` over [-half_m, half_m] (a fine mesh whose
/// triangles are about a pixel in size, as on a real wall).
AnalyticWall refined(AnalyticWall wall, double spacing_m, double half_m);

/// The four walls of the issue (heights about the wall plane z_F = 0, all within +-0.05 m).
AnalyticWall tiltedPlane();
AnalyticWall step();
AnalyticWall rectangularHole();  ///< one hole within [far, near] and one deeper than far
AnalyticWall vGroove();

/// A square camera of `side_px` pixels of `pixel_m` [m] that averages `samples` rays over an
/// edge pixel (DepthCameraParams::samples_per_pixel), with support heights for `support_slope`
/// [m/m] (0: none).
DepthCameraParams sampledCamera(int side_px, double pixel_m, int samples, double support_slope = 0.0);

/// T from x y z [m] and roll pitch yaw [deg] (R = Rz(yaw) Ry(pitch) Rx(roll)).
Pose pose(double x, double y, double z, double roll_deg, double pitch_deg, double yaw_deg);

}  // namespace climbsim::scene::testing
