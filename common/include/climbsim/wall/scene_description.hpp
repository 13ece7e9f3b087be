#pragma once
/// @file
/// A scene file after loading (docs/scene-files.md#scene-xml): the tree of parts with their offsets
/// and meshes, the run-time elements and the sensors. Produced by loadSceneDescription().
///
/// Names: every part is an insertion point. Its full name is its parent's full name, ':'
/// and its own name; the root is "ROOT" (`ROOT:WORLD:ROBOT`). See scene_xml.hpp for how
/// `attached_to` is resolved.

#include <cstdint>
#include <string>
#include <vector>

#include "climbsim/wall/mesh_file.hpp"
#include "climbsim/wall/triangle_mesh.hpp"

namespace climbsim::scene {

/// One part (one insertion point). parts[0] is ROOT; parents come before their children.
struct PartInfo {
  std::string name;       ///< short name ("ROOT" for the root)
  std::string full_name;  ///< "ROOT:...:name"
  int parent = -1;        ///< index into SceneDescription::parts; -1 for ROOT only
  Pose T_parent_part = Pose::Identity();  ///< its `offset` (x y z [m], roll pitch yaw [deg])
  int mesh = -1;          ///< index into SceneDescription::meshes; -1: a pure frame or a nested file
  std::string where;      ///< "<scene file>:<line>" of its declaration ("" for ROOT)
};

/// An `element` of type "3d Pose": at run time its pose replaces the offset of its part,
/// i.e. it is T_parent_part of that part (see Scene::setPose).
struct PoseElement {
  std::string name;
  int part = -1;                 ///< the part it moves (never ROOT)
  bool angles_in_degrees = false;  ///< angle_type="deg" (true) or "rad" (false)
  std::string where;
};

/// An `element` of type "Switch": switches its part and everything attached below it on
/// (switch_mode -3) or off (-1).
struct SwitchElement {
  std::string name;
  int part = -1;
  bool on = true;  ///< switch_mode -3; Scene::setSwitch changes it
  std::string where;
};

/// A `distance_sensor` (2D laser scanner): beams in the sensor frame's x-y plane,
/// counter-clockwise about its z, symmetric about its x axis.
struct DistanceSensorInfo {
  std::string name;
  int part = -1;                                 ///< part it is attached to
  Pose T_part_sensor = Pose::Identity();         ///< its `offset`
  double max_distance_m = 0.0;                   ///< > 0
  double scan_angle_range_rad = 0.0;             ///< total field of view, in (0, 2 pi]
  double angular_resolution_rad = 0.0;           ///< between beams, > 0
  std::string where;
};

/// A `camera` (orthographic): looks along its frame's -z; near and far limits are distances
/// along the view direction [m]. Sizes are 0 where the file does not give them.
struct CameraInfo {
  std::string name;
  int part = -1;
  Pose T_part_camera = Pose::Identity();  ///< its `offset`
  std::string type;                       ///< "orthographic"
  double near_limit_m = 0.0;
  double far_limit_m = 0.0;               ///< 0: not given
  int width_px = 0;
  int height_px = 0;
  double width_m = 0.0;                   ///< extent on the wall along the camera's x
  double height_m = 0.0;                  ///< extent along the camera's y
  std::string where;
};

/// A whole scene, nested files expanded.
struct SceneDescription {
  std::string file;                 ///< the top scene file as given
  std::vector<PartInfo> parts;      ///< parts[0] = ROOT
  std::vector<LocalMesh> meshes;    ///< one per distinct mesh file
  std::vector<PoseElement> pose_elements;
  std::vector<SwitchElement> switches;
  std::vector<DistanceSensorInfo> distance_sensors;
  std::vector<CameraInfo> cameras;
};

}  // namespace climbsim::scene
