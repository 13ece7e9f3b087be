#pragma once
/// @file
/// The SIMVIS3D-style scene XML (docs/scene-files.md#scene-xml), read with tinyxml2.
///
/// ```
/// <scene>
///   <part name="WORLD" file="walls/pylon.xml" attached_to="ROOT" offset="0 0 0 0 0 0"/>
///   <part name="CUBE" file="meshes/cube.ply" attached_to="BRIDGE" offset="2 0 0 0 0 270"/>
///   <part name="ROBOT" file="" attached_to="WALL"/>
///   <element name="robot_pose" type="3d Pose" angle_type="rad" attached_to="ROBOT"/>
///   <element name="switch" type="Switch" switch_mode="-3" attached_to="ROBOT"/>
///   <distance_sensor name="laser_scanner" max_distance="4" scan_angle_range="240"
///      angular_resolution="0.352423" offset="0 0 0.35 0 20 0" attached_to="TCP"/>
///   <camera name="depth_cam" type="orthographic" near_limit="0.1" far_limit="0.2"
///      width="256" height="256" size="0.8 0.8" attached_to="DEPTH_CAMERA"/>
/// </scene>
/// ```
///
/// Tags and attributes (anything else is an error):
///  - `part`: name (required, no ':'; not "ROOT"), attached_to (required), file (optional;
///    absent or empty: a pure frame; ending in .xml: a nested scene file whose contents are
///    inserted under this part; anything else: a mesh read with assimp), offset (optional,
///    "x y z roll pitch yaw" in m and degrees, default zero; rotation convention in
///    pose_offset.hpp). Relative paths are resolved against the directory of the file
///    that names them.
///  - `element`: name (required, unique among elements), type "3d Pose" with angle_type
///    "rad" or "deg", or type "Switch" with switch_mode -3 (on) or -1 (off); attached_to.
///  - `distance_sensor`: name, attached_to, max_distance [m], scan_angle_range [deg],
///    angular_resolution [deg], offset (optional).
///  - `camera`: name, attached_to, type "orthographic", near_limit [m], far_limit [m]
///    (optional), width and height [px] (optional, positive integers), size (optional,
///    "w h" or "w" [m] on the wall; absent: the run's robot's view, robotDepthViewM), offset
///    (optional).
/// Sensor names are unique among sensors of their kind.
///
/// attached_to:
///  - "ROOT": the root of the file (in a nested file: the part that includes it);
///  - a full path "ROOT:A:B", walked from the file's root through the parts' names; each
///    step must be unique among the children;
///  - a short name "B": the one part of that name declared in this file or in any file it
///    includes (directly or not); two of them is an error naming both. Parts that are never
///    addressed may share names.
/// A part may be attached to one declared later in the file. Parts attached to each other in
/// a ring, and files including themselves, are a "cycle of insertion points".
///
/// Every problem is a ConfigError with one line "<file>:<line>: <what>" naming the attribute
/// and its value, e.g. `walls.xml:7: part "CUBE": attached_to="BRIDGE" names no insertion point`.

#include <string>

#include "climbsim/wall/scene_description.hpp"

namespace climbsim::scene {

/// Loads `path` and every file it names (nested scenes, meshes; each mesh file once).
/// Throws ConfigError.
SceneDescription loadSceneDescription(const std::string& path);

}  // namespace climbsim::scene
