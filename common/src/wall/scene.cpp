#include "climbsim/wall/scene.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "climbsim/errors.hpp"
#include "climbsim/wall/pose_offset.hpp"
#include "climbsim/wall/scene_xml.hpp"

namespace climbsim::scene {

Scene::Scene(SceneDescription description)
    : description_(std::move(description)),
      moving_(description_.parts.size(), 0),
      switched_off_(description_.parts.size(), 0) {
  for (const auto& part : description_.parts) local_.push_back(part.T_parent_part);
  for (const auto& element : description_.pose_elements) moving_[element.part] = 1;
  // Parents precede children (SceneDescription), so one pass carries the flag down.
  for (std::size_t i = 1; i < description_.parts.size(); ++i) {
    moving_[i] = moving_[i] || moving_[description_.parts[i].parent];
  }
  for (const auto& s : description_.switches) {
    if (!s.on) switched_off_[s.part] = 1;
  }
}

void Scene::fail(const std::string& problem) const { throw ConfigError("scene " + description_.file + ": " + problem); }

std::size_t Scene::partIndex(const std::string& name) const {
  const auto& parts = description_.parts;
  if (name.find(':') != std::string::npos || name == "ROOT") {
    for (std::size_t i = 0; i < parts.size(); ++i) {
      if (parts[i].full_name == name) return i;
    }
    fail("no part with the full name '" + name + "'");
  }
  std::vector<std::size_t> found;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    if (parts[i].name == name) found.push_back(i);
  }
  if (found.size() > 1) {
    fail("part name '" + name + "' is ambiguous (" + parts[found[0]].full_name + ", " + parts[found[1]].full_name +
         "); give the full name");
  }
  if (found.empty()) fail("no part named '" + name + "'");
  return found[0];
}

const PoseElement& Scene::poseElement(const std::string& element) const {
  for (const auto& e : description_.pose_elements) {
    if (e.name == element) return e;
  }
  fail("no element of type \"3d Pose\" named '" + element + "'");
}

const SwitchElement& Scene::switchElement(const std::string& element) const {
  for (const auto& e : description_.switches) {
    if (e.name == element) return e;
  }
  fail("no element of type \"Switch\" named '" + element + "'");
}

void Scene::setPose(const std::string& element, const Pose& T_parent_part_new) {
  const auto& e = poseElement(element);
  if (!T_parent_part_new.matrix().allFinite()) {
    throw std::invalid_argument("scene: pose of element '" + element + "' is not finite");
  }
  local_[e.part] = T_parent_part_new;
}

void Scene::setPose(const std::string& element, const std::array<double, 6>& xyz_rpy) {
  const double to_rad = poseElement(element).angles_in_degrees ? M_PI / 180.0 : 1.0;
  setPose(element, poseFromXyzRpy(xyz_rpy[0], xyz_rpy[1], xyz_rpy[2], xyz_rpy[3] * to_rad, xyz_rpy[4] * to_rad,
                                  xyz_rpy[5] * to_rad));
}

void Scene::setSwitch(const std::string& element, bool on) {
  switchElement(element);
  bool changed = false;
  for (auto& s : description_.switches) {
    if (s.name == element && s.on != on) {
      s.on = on;
      changed = true;
    }
  }
  if (!changed) return;
  std::fill(switched_off_.begin(), switched_off_.end(), 0);
  for (const auto& s : description_.switches) {
    if (!s.on) switched_off_[s.part] = 1;
  }
  static_valid_ = false;
}

Pose Scene::worldPose(std::size_t part) const {
  Pose T = local_.at(part);
  for (int p = description_.parts[part].parent; p >= 0; p = description_.parts[p].parent) T = local_[p] * T;
  return T;
}

Pose Scene::worldPose(const std::string& name) const { return worldPose(partIndex(name)); }

bool Scene::visible(std::size_t part) const {
  for (int p = static_cast<int>(part); p >= 0; p = description_.parts[p].parent) {
    if (switched_off_[p]) return false;
  }
  return true;
}

void Scene::appendPart(std::size_t part, const Pose& T_world_part, TriangleMesh& out) const {
  const LocalMesh& mesh = description_.meshes[description_.parts[part].mesh];
  const auto base = static_cast<std::uint32_t>(out.vertices_m.size());
  const Eigen::Isometry3f T = T_world_part.cast<float>();
  for (const auto& v : mesh.vertices_m) out.vertices_m.push_back(T * v);
  for (const auto& t : mesh.triangles) {
    out.triangles.push_back({base + t[0], base + t[1], base + t[2]});
    out.part_ids.push_back(static_cast<std::uint32_t>(part));
  }
}

const TriangleMesh& Scene::staticMesh() const {
  if (!static_valid_) {
    static_mesh_ = TriangleMesh{};
    auto isStatic = [&](std::size_t i) { return description_.parts[i].mesh >= 0 && !moving_[i] && visible(i); };
    std::size_t vertices = 0, triangles = 0;  // reserved at once: millions of triangles, copied once
    for (std::size_t i = 0; i < description_.parts.size(); ++i) {
      if (!isStatic(i)) continue;
      vertices += description_.meshes[description_.parts[i].mesh].vertices_m.size();
      triangles += description_.meshes[description_.parts[i].mesh].triangles.size();
    }
    static_mesh_.vertices_m.reserve(vertices);
    static_mesh_.triangles.reserve(triangles);
    static_mesh_.part_ids.reserve(triangles);
    for (std::size_t i = 0; i < description_.parts.size(); ++i) {
      if (isStatic(i)) appendPart(i, worldPose(i), static_mesh_);
    }
    static_valid_ = true;
  }
  return static_mesh_;
}

std::vector<MovingPart> Scene::movingParts() const {
  std::vector<MovingPart> out;
  for (std::size_t i = 0; i < description_.parts.size(); ++i) {
    if (description_.parts[i].mesh >= 0 && moving_[i] && visible(i)) {
      out.push_back({static_cast<std::uint32_t>(i), worldPose(i), &description_.meshes[description_.parts[i].mesh]});
    }
  }
  return out;
}

TriangleMesh Scene::movingMesh() const {
  TriangleMesh out;
  for (const auto& m : movingParts()) appendPart(m.part, m.T_world_part, out);
  return out;
}

TriangleMesh Scene::worldMesh() const {
  TriangleMesh out = staticMesh();
  const TriangleMesh moving = movingMesh();
  const auto base = static_cast<std::uint32_t>(out.vertices_m.size());
  out.vertices_m.insert(out.vertices_m.end(), moving.vertices_m.begin(), moving.vertices_m.end());
  for (const auto& t : moving.triangles) out.triangles.push_back({base + t[0], base + t[1], base + t[2]});
  out.part_ids.insert(out.part_ids.end(), moving.part_ids.begin(), moving.part_ids.end());
  return out;
}

std::vector<std::uint32_t> Scene::partsMovedBy(const std::string& element) const {
  const int top = poseElement(element).part;
  std::vector<char> inside(description_.parts.size(), 0);
  std::vector<std::uint32_t> out;
  inside[top] = 1;
  // Parents precede children: descendants of `top` come after it.
  for (std::size_t i = top; i < description_.parts.size(); ++i) {
    if (static_cast<int>(i) != top && !(description_.parts[i].parent >= 0 && inside[description_.parts[i].parent])) {
      continue;
    }
    inside[i] = 1;
    out.push_back(static_cast<std::uint32_t>(i));
  }
  return out;
}

const CameraInfo& Scene::camera(const std::string& name) const {
  for (const auto& c : description_.cameras) {
    if (c.name == name) return c;
  }
  fail("no camera named '" + name + "'");
}

const DistanceSensorInfo& Scene::distanceSensor(const std::string& name) const {
  for (const auto& s : description_.distance_sensors) {
    if (s.name == name) return s;
  }
  fail("no distance_sensor named '" + name + "'");
}

Pose Scene::sensorPose(const std::string& name) const {
  for (const auto& c : description_.cameras) {
    if (c.name == name) return worldPose(c.part) * c.T_part_camera;
  }
  for (const auto& s : description_.distance_sensors) {
    if (s.name == name) return worldPose(s.part) * s.T_part_sensor;
  }
  fail("no camera or distance_sensor named '" + name + "'");
}

Scene loadScene(const std::string& path) { return Scene(loadSceneDescription(path)); }

}  // namespace climbsim::scene
