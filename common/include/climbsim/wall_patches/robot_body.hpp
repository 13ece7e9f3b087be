#pragma once
/// @file
/// A simple robot body for scenes: enough geometry for tests to check that the robot's own
/// parts never reach the depth image.

#include "climbsim/wall_patches/surface_mesh.hpp"

namespace climbsim::surface {

/// Robot frame R (deploy/robots/cromsci.yaml): origin at the body centre in the sealing
/// plane, z away from the wall, x through chamber 1. The body is a closed cylinder of
/// diameter 0.80 m from z = 0.03 to 0.20 m (48 sides); three wheels are closed cylinders of
/// radius 0.05 m and width 0.04 m, axles along the radius, centres at r = 0.26 m,
/// z = 0.05 m (touching the wall) and angles 0, 120, 240 deg (chambers 1, 3, 5).
SurfaceMesh robotBodyMesh();

}  // namespace climbsim::surface
