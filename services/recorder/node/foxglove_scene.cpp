#include "node/foxglove_scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace climbsim::recorder {
namespace {

/// Angular step of the chambers' arcs in their triangle lists [rad].
constexpr double kArcStepRad = 5.0 * M_PI / 180.0;

foxglove::Time stamp(std::int64_t t_ns) {
  foxglove::Time t;
  t.sec(static_cast<std::uint32_t>(t_ns / 1'000'000'000));
  t.nsec(static_cast<std::uint32_t>(t_ns % 1'000'000'000));
  return t;
}

foxglove::Point3 point(double x, double y) {
  foxglove::Point3 p;
  p.x(x);
  p.y(y);
  p.z(0.0);
  return p;
}

foxglove::Color colour(double r, double g, double b, double a) {
  foxglove::Color c;
  c.r(r);
  c.g(g);
  c.b(b);
  c.a(a);
  return c;
}

/// An arrow from (x, y, 0) along R's +z (towards_wall false) or -z, `length_m` long.
foxglove::ArrowPrimitive arrow(double x, double y, double length_m, bool towards_wall, const foxglove::Color& c) {
  foxglove::ArrowPrimitive a;
  a.pose().position().x(x);
  a.pose().position().y(y);
  // An arrow points along its pose's x; a quarter turn about y takes x to -z (+z for -1/2 pi).
  const double half = (towards_wall ? 0.5 : -0.5) * M_PI / 2.0;
  a.pose().orientation().w(std::cos(half));
  a.pose().orientation().y(std::sin(half));
  a.head_length(std::min(0.03, 0.5 * length_m));
  a.shaft_length(std::max(0.0, length_m - a.head_length()));
  a.shaft_diameter(0.008);
  a.head_diameter(0.02);
  a.color(c);
  return a;
}

/// The triangles of a chamber: a fan for the centre disc, a strip between the arcs of a sector.
foxglove::TriangleListPrimitive chamberTriangles(const RobotGeometry::Chamber& chamber) {
  foxglove::TriangleListPrimitive t;
  t.pose().orientation().w(1.0);
  const int n = std::max(1, static_cast<int>(std::ceil(chamber.span_rad / kArcStepRad)));
  const double start = chamber.centre_angle_rad - chamber.span_rad / 2.0;
  for (int i = 0; i < n; ++i) {
    const double a0 = start + chamber.span_rad * i / n;
    const double a1 = start + chamber.span_rad * (i + 1) / n;
    const double r1 = chamber.inner_radius_m;
    const double r2 = chamber.outer_radius_m;
    const auto at = [](double r, double a) { return point(r * std::cos(a), r * std::sin(a)); };
    for (const auto& p : {at(r1, a0), at(r2, a0), at(r2, a1)}) t.points().push_back(p);
    if (r1 > 0.0) {
      for (const auto& p : {at(r1, a0), at(r2, a1), at(r1, a1)}) t.points().push_back(p);
    }
  }
  return t;
}

}  // namespace

foxglove::FrameTransforms robotTransform(const climbsim::RobotState& pose, std::int64_t t_ns) {
  foxglove::FrameTransform tf;
  tf.timestamp(stamp(t_ns));
  tf.parent_frame_id("wall");
  tf.child_frame_id("robot");
  tf.translation().x(pose.position_m()[0]);
  tf.translation().y(pose.position_m()[1]);
  tf.translation().z(pose.position_m()[2]);
  tf.rotation().w(pose.orientation_wxyz()[0]);
  tf.rotation().x(pose.orientation_wxyz()[1]);
  tf.rotation().y(pose.orientation_wxyz()[2]);
  tf.rotation().z(pose.orientation_wxyz()[3]);
  foxglove::FrameTransforms out;
  out.transforms().push_back(tf);
  return out;
}

foxglove::SceneUpdate robotScene(const RobotGeometry& geometry, const climbsim::ChamberState* chambers,
                                 double ambient_pa, const climbsim::DriveState* drive,
                                 const climbsim::AdhesionForce* force, std::int64_t t_ns) {
  foxglove::SceneEntity entity;
  entity.timestamp(stamp(t_ns));
  entity.frame_id("robot");
  entity.id("robot");
  entity.frame_locked(true);
  for (const auto& chamber : geometry.chambers) {
    auto t = chamberTriangles(chamber);
    double share = 0.0;
    const auto index = static_cast<std::size_t>(chamber.id);
    if (chambers != nullptr && index < chambers->pressure_pa().size()) {
      share = std::clamp((ambient_pa - chambers->pressure_pa()[index]) / kFullSuctionPa, 0.0, 1.0);
    }
    t.color(colour(share, 0.2, 1.0 - share, 0.8));
    entity.triangles().push_back(std::move(t));
  }
  if (drive != nullptr) {
    for (std::size_t i = 0; i < geometry.wheels.size() && i < drive->wheels().size(); ++i) {
      const auto& p = geometry.wheels[i].p_RobotWheel;
      entity.arrows().push_back(arrow(p.x_m, p.y_m, kWheelArrowMPerN * drive->wheels()[i].normal_force_n(), false,
                                      colour(1.0, 0.8, 0.0, 1.0)));
    }
  }
  if (force != nullptr) {
    entity.arrows().push_back(arrow(force->pf_x_m(), force->pf_y_m(), kDownforceArrowMPerN * force->downforce_n(),
                                    true, colour(0.0, 1.0, 0.3, 1.0)));
  }
  foxglove::SceneUpdate update;
  update.entities().push_back(std::move(entity));
  return update;
}

foxglove::Grid depthGridMessage(const climbsim::DepthGrid& grid) {
  foxglove::Grid out;
  out.timestamp(stamp(grid.t_ns()));
  out.frame_id("robot");
  const std::uint32_t n = grid.size();
  const double half_m = 0.5 * n * grid.cell_m();
  out.pose().position().x(-half_m);
  out.pose().position().y(-half_m);
  out.pose().orientation().w(1.0);
  out.column_count(n);
  out.cell_size().x(grid.cell_m());
  out.cell_size().y(grid.cell_m());
  out.cell_stride(sizeof(float));
  out.row_stride(n * sizeof(float));
  foxglove::PackedElementField field;
  field.name("height_m");
  field.offset(0);
  field.type(foxglove::FLOAT32);
  out.fields().push_back(field);
  out.data().resize(static_cast<std::size_t>(n) * n * sizeof(float));
  for (std::uint32_t row = 0; row < n && grid.height_m().size() >= static_cast<std::size_t>(n) * n; ++row) {
    // Grid rows go up along y; the DepthGrid's row 0 is at +y.
    std::memcpy(out.data().data() + static_cast<std::size_t>(row) * n * sizeof(float),
                grid.height_m().data() + static_cast<std::size_t>(n - 1 - row) * n, n * sizeof(float));
  }
  return out;
}

}  // namespace climbsim::recorder
