#include "wheels_over_scene.hpp"

#include <Eigen/Geometry>
#include <spdlog/spdlog.h>

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <future>

#include "climbsim/errors.hpp"

#include "climbsim/wall/scene.hpp"
#include "climbsim/wall/scene_xml.hpp"

namespace climbsim::drive {

WheelsOverScene::WheelsOverScene(scene::WallCoverage coverage, std::vector<WheelMount> wheels)
    : coverage_(std::move(coverage)), wheels_(std::move(wheels)), named_(wheels_.size(), 0) {}

std::array<double, 2> WheelsOverScene::contactPoint(const DriveOutputs& outputs, std::size_t w) const {
  const auto& q = outputs.orientation_wxyz;
  const Eigen::Quaterniond R_W_R(q[0], q[1], q[2], q[3]);
  const Eigen::Vector3d p_W = Eigen::Vector3d(outputs.position_m[0], outputs.position_m[1], outputs.position_m[2]) +
                              R_W_R.normalized() * Eigen::Vector3d(wheels_[w].x_m, wheels_[w].y_m, 0.0);
  return {p_W.x(), p_W.y()};
}

std::vector<std::size_t> WheelsOverScene::newlyOverNothing(const DriveOutputs& outputs) {
  std::vector<std::size_t> found;
  for (std::size_t w = 0; w < wheels_.size(); ++w) {
    if (named_[w]) continue;
    const auto p = contactPoint(outputs, w);
    if (!coverage_.covered(p[0], p[1])) {
      named_[w] = 1;
      found.push_back(w);
    }
  }
  return found;
}

std::string WheelsOverScene::overNothingText(const DriveOutputs& outputs, std::size_t w, std::int64_t t_ns) const {
  const auto p = contactPoint(outputs, w);
  return fmt::format("wheel {} stands over nothing at t = {:.3f} s: no wall within {:.3f} m under its contact point "
                     "(x = {:.3f} m, y = {:.3f} m; past the edge of the scene, or a hole deeper than that); it carries "
                     "no load unless it rests on the hole's rim (summary.json wheels_over_nothing)",
                     w + 1, static_cast<double>(t_ns) * 1e-9, coverage_.reach(), p[0], p[1]);
}

namespace {

/// The 3d Pose element that places the robot in `description`: "robot_pose" (the scene
/// service's default) or the only one; ConfigError if neither.
std::string robotPoseElement(const scene::SceneDescription& description, const std::string& scene_file) {
  const auto& elements = description.pose_elements;
  const bool has_default =
      std::any_of(elements.begin(), elements.end(), [](const auto& e) { return e.name == "robot_pose"; });
  if (has_default) return "robot_pose";
  if (elements.size() == 1) return elements.front().name;
  throw ConfigError(scene_file + " has no 3d Pose element 'robot_pose'");
}

}  // namespace

WheelScene::WheelScene(const std::string& file) : WheelScene(scene::loadSceneDescription(file)) {}

WheelScene::WheelScene(scene::SceneDescription description) : scene_file(description.file) {
  pose_element = robotPoseElement(description, scene_file);
  reach_m = scene::coverageReach(description);
  world = std::make_shared<const scene::Scene>(std::move(description));
}

namespace {

/// A background chore while every process of the run starts: at a lower priority than the DDS
/// threads of this and the other processes (their leases are 4 s on a busy machine).
void lowerThisThreadsPriority() { ::setpriority(PRIO_PROCESS, static_cast<id_t>(::syscall(SYS_gettid)), 10); }

}  // namespace

WheelSceneLoading loadWheelSceneInBackground(const std::string& scene_file) {
  return std::async(std::launch::async, [scene_file] {
           lowerThisThreadsPriority();
           return std::make_shared<const WheelScene>(scene_file);
         }).share();
}

WheelSceneLoading wheelSceneInBackground(std::shared_ptr<const scene::SceneDescription> description) {
  return std::async(std::launch::async, [description] {
           lowerThisThreadsPriority();
           return std::make_shared<const WheelScene>(scene::SceneDescription(*description));
         }).share();
}

std::optional<WheelsOverScene> wheelCheckOnScene(const WheelSceneLoading& scene, const std::vector<WheelMount>& wheels) {
  if (!scene.valid()) return std::nullopt;
  try {
    const WheelScene& loaded = *scene.get();
    return WheelsOverScene(scene::wallCoverage(*loaded.world, loaded.pose_element, loaded.reach_m), wheels);
  } catch (const std::exception& e) {
    spdlog::warn("the wheels are not checked against the scene: {}", e.what());
    return std::nullopt;
  }
}

scene::SurfaceHeights surfaceUnderWheels(const WheelScene& scene, double patch_m) {
  return scene::surfaceHeights(*scene.world, scene.pose_element, scene.reach_m, scene::SurfaceHeights::kDefaultCell_m,
                               patch_m);
}

std::shared_ptr<const WheelGround> wheelGroundOfScene(const WheelSceneLoading& scene, double patch_m) {
  auto making = std::async(std::launch::async, [scene, patch_m] {
    lowerThisThreadsPriority();
    std::shared_ptr<const WheelScene> loaded;
    try {
      loaded = scene.get();
    } catch (const std::exception& e) {
      throw ConfigError(std::string("wall.wheels_on = surface: the wheels cannot stand on the scene: ") + e.what());
    }
    return std::make_shared<const scene::SurfaceHeights>(surfaceUnderWheels(*loaded, patch_m));
  });
  return std::make_shared<const WheelGround>(making.share());
}

}  // namespace climbsim::drive
