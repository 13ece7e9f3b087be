#include "climbsim/wall/robot_body_part.hpp"

#include <algorithm>
#include <utility>
#include <vector>

namespace climbsim::scene {

bool attachRobotBody(SceneDescription& scene, const std::string& pose_element, LocalMesh body) {
  const auto element = std::find_if(scene.pose_elements.begin(), scene.pose_elements.end(),
                                    [&](const PoseElement& e) { return e.name == pose_element; });
  if (element == scene.pose_elements.end() || element->part < 0) return false;
  const auto robot = static_cast<std::size_t>(element->part);
  // Parents precede children, so one pass marks the robot part's subtree.
  std::vector<char> under(scene.parts.size(), 0);
  under[robot] = 1;
  for (std::size_t i = robot + 1; i < scene.parts.size(); ++i) {
    const int parent = scene.parts[i].parent;
    under[i] = parent >= 0 && under[static_cast<std::size_t>(parent)];
  }
  for (std::size_t i = 0; i < scene.parts.size(); ++i) {
    if (under[i] && scene.parts[i].mesh >= 0) return false;
  }
  PartInfo part;
  part.name = kRobotBodyPart;
  part.full_name = scene.parts[robot].full_name + ":" + kRobotBodyPart;
  part.parent = static_cast<int>(robot);
  part.mesh = static_cast<int>(scene.meshes.size());
  part.where = body.file;
  scene.meshes.push_back(std::move(body));
  scene.parts.push_back(std::move(part));
  return true;
}

}  // namespace climbsim::scene
