#include "node/foxglove_scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace climbsim::recorder {
namespace {

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

/// Twice the signed area of the triangle (a, b, c): > 0 counter-clockwise.
double cross(const RobotGeometry::Point& a, const RobotGeometry::Point& b, const RobotGeometry::Point& c) {
  return (b.x_m - a.x_m) * (c.y_m - a.y_m) - (b.y_m - a.y_m) * (c.x_m - a.x_m);
}

/// Heading of the edge from a to b [rad].
double heading(const RobotGeometry::Point& a, const RobotGeometry::Point& b) {
  return std::atan2(b.y_m - a.y_m, b.x_m - a.x_m);
}

/// |a - b| wrapped to [0, pi] [rad].
double turn(double a, double b) {
  const double d = std::fmod(std::abs(a - b), 2.0 * M_PI);
  return d > M_PI ? 2.0 * M_PI - d : d;
}

/// The outline with its arcs sampled coarsely: a corner is kept where the outline turns by
/// kCornerRad or more, and along an arc every point where the heading has turned kArcStepRad
/// since the last one kept (the geometry samples arcs every degree; a viewer needs far fewer).
std::vector<RobotGeometry::Point> coarseOutline(const std::vector<RobotGeometry::Point>& outline) {
  constexpr double kCornerRad = 20.0 * M_PI / 180.0;
  constexpr double kArcStepRad = 6.0 * M_PI / 180.0;
  const std::size_t n = outline.size();
  if (n <= 3) return outline;
  std::vector<RobotGeometry::Point> out;
  double last_kept_heading = heading(outline[n - 1], outline[0]);
  for (std::size_t i = 0; i < n; ++i) {
    const double in = heading(outline[(i + n - 1) % n], outline[i]);
    const double out_heading = heading(outline[i], outline[(i + 1) % n]);
    if (turn(in, out_heading) >= kCornerRad || turn(last_kept_heading, out_heading) >= kArcStepRad) {
      out.push_back(outline[i]);
      last_kept_heading = out_heading;
    }
  }
  return out.size() >= 3 ? out : outline;
}

bool inside(const RobotGeometry::Point& p, const RobotGeometry::Point& a, const RobotGeometry::Point& b,
            const RobotGeometry::Point& c) {
  return cross(a, b, p) >= 0.0 && cross(b, c, p) >= 0.0 && cross(c, a, p) >= 0.0;
}

}  // namespace

std::vector<foxglove::TriangleListPrimitive> chamberShapes(const RobotGeometry& geometry) {
  std::vector<foxglove::TriangleListPrimitive> out;
  for (const auto& chamber : geometry.chambers) {
    foxglove::TriangleListPrimitive t;
    t.pose().orientation().w(1.0);
    // Ear clipping of the counter-clockwise outline: cut off a convex corner whose triangle
    // holds no other corner, until three are left.
    std::vector<RobotGeometry::Point> left = coarseOutline(chamber.outline_Robot);
    while (left.size() > 3) {
      const std::size_t n = left.size();
      std::size_t ear = n;
      for (std::size_t i = 0; i < n && ear == n; ++i) {
        const auto& a = left[(i + n - 1) % n];
        const auto& b = left[i];
        const auto& c = left[(i + 1) % n];
        if (cross(a, b, c) <= 0.0) continue;
        bool empty = true;
        for (std::size_t j = 0; j < n && empty; ++j) {
          if (j != i && j != (i + 1) % n && j != (i + n - 1) % n && inside(left[j], a, b, c)) empty = false;
        }
        if (empty) ear = i;
      }
      if (ear == n) ear = 0;  // no clean ear (collinear runs): cut the first corner
      for (const std::size_t j : {(ear + n - 1) % n, ear, (ear + 1) % n}) {
        t.points().push_back(point(left[j].x_m, left[j].y_m));
      }
      left.erase(left.begin() + static_cast<std::ptrdiff_t>(ear));
    }
    if (left.size() == 3) {
      for (const auto& p : left) t.points().push_back(point(p.x_m, p.y_m));
    }
    out.push_back(std::move(t));
  }
  return out;
}

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

foxglove::SceneUpdate robotScene(const RobotGeometry& geometry,
                                 const std::vector<foxglove::TriangleListPrimitive>& shapes,
                                 const climbsim::ChamberState* chambers, double ambient_pa,
                                 const climbsim::DriveState* drive, const climbsim::AdhesionForce* force,
                                 std::int64_t t_ns) {
  foxglove::SceneEntity entity;
  entity.timestamp(stamp(t_ns));
  entity.frame_id("robot");
  entity.id("robot");
  entity.frame_locked(true);
  for (std::size_t k = 0; k < geometry.chambers.size() && k < shapes.size(); ++k) {
    const auto& chamber = geometry.chambers[k];
    auto t = shapes[k];
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

namespace {
/// foxglove.Grid of `columns` x `rows` heights [m] of square cells of `cell_m` (row-major, row 0
/// at R's +y edge), in frame "robot", centred on R's origin; zeros unless heights holds them all.
foxglove::Grid heightGrid(std::int64_t t_ns, std::uint32_t columns, std::uint32_t rows, double cell_m,
                          const std::vector<float>& heights) {
  foxglove::Grid out;
  out.timestamp(stamp(t_ns));
  out.frame_id("robot");
  out.pose().position().x(-0.5 * columns * cell_m);
  out.pose().position().y(-0.5 * rows * cell_m);
  out.pose().orientation().w(1.0);
  out.column_count(columns);
  out.cell_size().x(cell_m);
  out.cell_size().y(cell_m);
  out.cell_stride(sizeof(float));
  out.row_stride(columns * sizeof(float));
  foxglove::PackedElementField field;
  field.name("height_m");
  field.offset(0);
  field.type(foxglove::FLOAT32);
  out.fields().push_back(field);
  const std::size_t row_bytes = static_cast<std::size_t>(columns) * sizeof(float);
  out.data().resize(row_bytes * rows);
  for (std::uint32_t row = 0; row < rows && heights.size() >= static_cast<std::size_t>(columns) * rows; ++row) {
    // Grid rows go up along y; the image's row 0 is at +y.
    std::memcpy(out.data().data() + row * row_bytes, heights.data() + static_cast<std::size_t>(rows - 1 - row) * columns,
                row_bytes);
  }
  return out;
}
}  // namespace

foxglove::Grid depthGridMessage(const climbsim::DepthGrid& grid) {
  return heightGrid(grid.t_ns(), grid.size(), grid.size(), grid.cell_m(), grid.height_m());
}

foxglove::Grid depthImageMessage(const climbsim::DepthImage& image) {
  return heightGrid(image.t_ns(), image.width_px(), image.height_px(), image.pixel_size_m(), image.height_m());
}

}  // namespace climbsim::recorder
