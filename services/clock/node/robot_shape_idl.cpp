#include "robot_shape_idl.hpp"

#include "climbsim/robot/robot_description.hpp"
#include "climbsim/robot/robot_geometry.hpp"
#include "climbsim/robot_names.hpp"

namespace climbsim::clock {

climbsim::RobotShape robotShapeFromFile(const std::string& robot_file) {
  const RobotDescription description = loadRobotDescription(robotFileOf(robot_file));
  const RobotGeometry geometry = computeGeometry(description);
  climbsim::RobotShape shape;
  shape.name(description.name);
  shape.has_reservoir(geometry.has_reservoir);
  shape.engine_count(static_cast<std::uint32_t>(description.engines.count));
  if (!geometry.has_reservoir) {
    for (int c : description.engines.chambers) shape.engine_chambers().push_back(static_cast<std::uint32_t>(c));
  }
  shape.engine_dp_max_pa(description.engines.dp_max_pa);
  shape.engine_speed_lag_s(description.engines.speed_lag_s);
  for (const auto& c : geometry.chambers) {
    climbsim::RobotChamber chamber;
    chamber.number(static_cast<std::uint32_t>(c.number));
    chamber.volume_m3(c.volume_m3);
    chamber.area_m2(c.area_m2);
    chamber.centroid_x_m(c.p_RobotCentroid.x_m);
    chamber.centroid_y_m(c.p_RobotCentroid.y_m);
    for (const auto& p : c.outline_Robot) {
      chamber.outline_x_m().push_back(p.x_m);
      chamber.outline_y_m().push_back(p.y_m);
    }
    shape.chambers().push_back(chamber);
  }
  for (const auto& s : geometry.segments) {
    climbsim::RobotSegment segment;
    segment.name(s.name);
    segment.volume_a(s.volume_a);
    segment.volume_b(s.volume_b);
    segment.length_m(s.length_m);
    shape.segments().push_back(segment);
  }
  for (const auto& w : geometry.wheels) {
    climbsim::RobotWheel wheel;
    wheel.kind(toString(w.kind));
    wheel.x_m(w.p_RobotWheel.x_m);
    wheel.y_m(w.p_RobotWheel.y_m);
    wheel.radius_m(w.radius_m);
    shape.wheels().push_back(wheel);
  }
  return shape;
}

}  // namespace climbsim::clock
