#pragma once
/// @file
/// The robot's body as a mesh, from its robot file (docs/robot-files.md#the-body-mesh): what the
/// scene hangs under the robot's pose (the laser scanner sees it; the depth image never does)
/// and what the viewer draws.

#include <array>
#include <cstdint>
#include <vector>

#include "climbsim/robot/robot_geometry.hpp"
#include "climbsim/wall_patches/surface_mesh.hpp"

namespace climbsim::surface {

/// The body's bottom and top above the sealing plane (z of R) [m].
inline constexpr float kBodyBottomM = 0.03f;
inline constexpr float kBodyTopM = 0.20f;
/// Tyre widths along the axle [m] by wheel kind, and the number of sides of a wheel's cylinder.
inline constexpr float kSteerableTyreM = 0.04f;
inline constexpr float kFixedTyreM = 0.05f;
inline constexpr float kCasterTyreM = 0.025f;
inline constexpr int kWheelSides = 24;

/// The body and wheels of `geometry` in the robot frame R (origin at the body centre in the
/// sealing plane, z away from the wall), each piece a closed mesh with outward normals:
///  - the body: body_outline_Robot extruded from z = kBodyBottomM to kBodyTopM (the top and
///    bottom faces ear-clipped from the outline, so the top face's area is the outline's);
///  - each wheel: a cylinder of its radius_m centred at its contact point's (x, y) and
///    z = radius_m (touching the wall). Steerable: axle along the radius through the contact
///    point (rolling about R's origin), kSteerableTyreM wide; fixed: axle along R's y (rolling
///    along x), kFixedTyreM wide; caster: axle along y (its rest direction), kCasterTyreM wide.
SurfaceMesh robotBodyMesh(const RobotGeometry& geometry);

/// Triangles (index triples into `outline`, counter-clockwise) covering the simple polygon
/// `outline` (counter-clockwise, not closed) by ear clipping: n - 2 triangles whose areas sum
/// to the polygon's.
std::vector<std::array<std::uint32_t, 3>> triangulatePolygon(const std::vector<RobotGeometry::Point>& outline);

}  // namespace climbsim::surface
