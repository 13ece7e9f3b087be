#pragma once
/// @file
/// The scene graph at run time (docs/design.md#models, docs/scene-files.md#scene-xml): world poses
/// of parts and sensors, the 3d Pose and Switch elements, and the triangles handed to the depth
/// camera and the laser scanner (triangle_mesh.hpp).
///
/// Frames: the world frame is ROOT's. worldPose(part) = T_world_part, the product of the
/// T_parent_part along the path from ROOT.
///
/// 3d Pose elements *replace* the offset of the part they are attached to: after
/// setPose(e, T), T_parent_part of that part is T (the XML offset is only its pose until
/// the first setPose). So a robot part attached to the wall part W moves by T_W_R exactly.
///
/// Static and moving parts: a part moves if a 3d Pose element is attached to it or to any of
/// its ancestors. The triangles of static parts are transformed to the world once and kept
/// (staticMesh()); moving parts are transformed on request (movingMesh()). Part ids in the
/// meshes are indices into parts().

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "climbsim/wall/triangle_mesh.hpp"
#include "climbsim/wall/scene_description.hpp"

namespace climbsim::scene {

/// A moving part with a mesh, at its current world pose.
struct MovingPart {
  std::uint32_t part = 0;            ///< index into Scene::parts()
  Pose T_world_part;                 ///< current world pose
  const LocalMesh* mesh = nullptr;   ///< triangles in the part frame
};

class Scene {
 public:
  explicit Scene(SceneDescription description);

  const SceneDescription& description() const { return description_; }
  const std::vector<PartInfo>& parts() const { return description_.parts; }

  /// Index of the part `name` names: "ROOT", a full name "ROOT:A:B" or a unique short name.
  /// ConfigError "scene <file>: ..." if it names none or several.
  std::size_t partIndex(const std::string& name) const;

  /// Sets the pose of the part the 3d Pose element `element` is attached to, relative to that
  /// part's parent: T_parent_part = T_parent_part_new (replaces its offset).
  /// ConfigError if there is no such element; std::invalid_argument if not finite.
  void setPose(const std::string& element, const Pose& T_parent_part_new);
  /// The same from x y z [m] and roll pitch yaw in the element's angle_type (rad or deg),
  /// rotation R = Rz(yaw) Ry(pitch) Rx(roll) as for offsets.
  void setPose(const std::string& element, const std::array<double, 6>& xyz_rpy);
  /// Switches the subtree of the Switch element `element`'s part on or off. ConfigError if
  /// there is no such element.
  void setSwitch(const std::string& element, bool on);

  /// T_world_part of the part `name` names (see partIndex) [m].
  Pose worldPose(const std::string& name) const;
  Pose worldPose(std::size_t part) const;
  /// T_parent_part now in force (the offset or the last setPose).
  const Pose& localPose(std::size_t part) const { return local_[part]; }

  /// True if the part and all its ancestors are switched on.
  bool visible(std::size_t part) const;
  /// True if a 3d Pose element moves the part (attached to it or to an ancestor).
  bool moving(std::size_t part) const { return moving_[part] != 0; }

  /// Triangles of the visible static parts in the world frame. Built at the first call and
  /// after a Switch changed; pose elements never change it.
  const TriangleMesh& staticMesh() const;
  /// The visible moving parts that carry a mesh, at their current world poses.
  std::vector<MovingPart> movingParts() const;
  /// Triangles of the visible moving parts in the world frame.
  TriangleMesh movingMesh() const;
  /// staticMesh() and movingMesh() together.
  TriangleMesh worldMesh() const;

  /// The pose element's part and every part below it, sorted: the ids the depth camera
  /// leaves out when `element` places the robot. ConfigError if there is no such element.
  std::vector<std::uint32_t> partsMovedBy(const std::string& element) const;
  const PoseElement& poseElement(const std::string& element) const;

  /// World pose of the camera or distance sensor `name` (T_world_sensor = T_world_part *
  /// offset). ConfigError if there is none of that name.
  Pose sensorPose(const std::string& name) const;
  const CameraInfo& camera(const std::string& name) const;
  const DistanceSensorInfo& distanceSensor(const std::string& name) const;

 private:
  const SwitchElement& switchElement(const std::string& element) const;
  void appendPart(std::size_t part, const Pose& T_world_part, TriangleMesh& out) const;
  [[noreturn]] void fail(const std::string& problem) const;

  SceneDescription description_;
  std::vector<Pose, Eigen::aligned_allocator<Pose>> local_;
  std::vector<char> moving_;
  std::vector<char> switched_off_;  ///< by a Switch element attached to this part
  mutable bool static_valid_ = false;
  mutable TriangleMesh static_mesh_;
};

/// Loads a scene file (loadSceneDescription) into a Scene. Throws ConfigError.
Scene loadScene(const std::string& path);

}  // namespace climbsim::scene
