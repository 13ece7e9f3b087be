#include "robot_shape.hpp"

#include "climbsim/wall_patches/robot_body.hpp"

namespace climbsim::viewer {

namespace {
nlohmann::json points(const std::vector<RobotGeometry::Point>& line) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& p : line) out.push_back({p.x_m, p.y_m});
  return out;
}

const char* kindName(RobotGeometry::SegmentKind kind) {
  switch (kind) {
    case RobotGeometry::SegmentKind::kOuter: return "outer";
    case RobotGeometry::SegmentKind::kRadial: return "radial";
    case RobotGeometry::SegmentKind::kInner: return "inner";
    case RobotGeometry::SegmentKind::kWall: return "wall";
  }
  return "unknown";
}
}  // namespace

nlohmann::json robotShapeJson(const RobotDescription& description, const RobotGeometry& geometry) {
  nlohmann::json chambers = nlohmann::json::array();
  for (const auto& chamber : geometry.chambers) {
    chambers.push_back({{"number", chamber.number},
                        {"outline", points(chamber.outline_Robot)},
                        {"centroid", {chamber.p_RobotCentroid.x_m, chamber.p_RobotCentroid.y_m}}});
  }
  nlohmann::json segments = nlohmann::json::array();
  for (const auto& segment : geometry.segments) {
    segments.push_back({{"name", segment.name},
                        {"kind", kindName(segment.kind)},
                        {"length_m", segment.length_m},
                        {"line", points(segment.centreline_Robot)}});
  }
  nlohmann::json wheels = nlohmann::json::array();
  for (const auto& wheel : geometry.wheels) {
    wheels.push_back({{"chamber", wheel.chamber_number},
                      {"kind", toString(wheel.kind)},
                      {"radius_m", wheel.radius_m},
                      {"position", {wheel.p_RobotWheel.x_m, wheel.p_RobotWheel.y_m}}});
  }
  // The body mesh as the scene has it: the prism's triangles first, then the wheels'.
  RobotGeometry body_only = geometry;
  body_only.wheels.clear();
  const std::size_t body_triangles = surface::robotBodyMesh(body_only).triangles.size();
  const surface::SurfaceMesh mesh = surface::robotBodyMesh(geometry);
  nlohmann::json positions = nlohmann::json::array(), indices = nlohmann::json::array();
  for (const auto& v : mesh.vertices_m) {
    for (int k = 0; k < 3; ++k) positions.push_back(v[k]);
  }
  for (const auto& t : mesh.triangles) {
    for (const auto i : t) indices.push_back(i);
  }
  return {{"name", description.name},
          {"body_mesh", {{"positions", positions}, {"indices", indices}, {"body_triangles", body_triangles}}},
          {"body_radius_m", description.body.outerRadius()},
          {"body_outline", points(geometry.body_outline_Robot)},
          {"has_reservoir", geometry.has_reservoir},
          {"sealed_radius_m", geometry.ring_outer_radius_m},
          {"strip_width_m", geometry.strip_width_m},
          {"travel_m", description.sealing.travel_m},
          {"basic_gap_m", description.sealing.basic_gap_m},
          {"wheel_radius_m", description.wheels.front().radius_m},
          {"ambient_pa", description.gas.ambient_pressure_pa},
          {"desired_downforce_n", description.adhesion.desired_downforce_n},
          {"chambers", chambers},
          {"segments", segments},
          {"wheels", wheels}};
}

}  // namespace climbsim::viewer
