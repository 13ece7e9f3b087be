#pragma once
/// @file
/// The `offset` of the scene XML (docs/scene-files.md#scene-xml) and the rotation convention of
/// every angle triple in a scene: "x y z roll pitch yaw".
///
/// Convention (fixed axes, also called extrinsic x-y-z): first roll about the parent's x,
/// then pitch about the parent's y, then yaw about the parent's z:
///
///     R = Rz(yaw) * Ry(pitch) * Rx(roll),    p_parent = R * p_child + (x, y, z)
///
/// so T_parent_child maps child coordinates to parent coordinates.

#include <array>
#include <string>

#include "climbsim/wall/triangle_mesh.hpp"

namespace climbsim::scene {

/// R = Rz(yaw) Ry(pitch) Rx(roll), angles in radians, fixed axes (see the file comment).
Eigen::Matrix3d rotationFromRollPitchYaw(double roll_rad, double pitch_rad, double yaw_rad);

/// T_parent_child of an offset: translation (x, y, z) [m] and rotation
/// rotationFromRollPitchYaw(roll, pitch, yaw) [rad].
Pose poseFromXyzRpy(double x_m, double y_m, double z_m, double roll_rad, double pitch_rad, double yaw_rad);

/// Parses the text of an `offset` attribute, "x y z roll pitch yaw" (metres, degrees),
/// whitespace-separated, exactly six finite numbers. On error returns false and writes a
/// one-line reason ("expected 6 numbers ..., got 5", "'1,5' is not a finite number") to
/// `problem`.
bool parseOffset(const std::string& text, Pose& pose, std::string& problem);

/// Parses one finite number (the whole text, locale-independent); false if it is not one.
bool parseNumber(const std::string& text, double& value);

}  // namespace climbsim::scene
