// Robot files of every layout: the shipped robots load, their geometry agrees with
// independent computations (areas and centroids by sampling the plane, strip lengths from the
// layout's dimensions), and bad layouts are one line each naming file, line, key and value.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>

#include "climbsim/errors.hpp"
#include "climbsim/robot/chamber_polygons.hpp"
#include "climbsim/robot/robot_description.hpp"
#include "climbsim/robot/robot_geometry.hpp"

namespace climbsim {
namespace {

constexpr double kPi = 3.14159265358979323846;
using Layout = RobotDescription::Layout;
using Kind = RobotDescription::WheelKind;

std::string shippedFile(const std::string& name) { return std::string(CLIMBSIM_ROBOTS_DIR) + "/" + name + ".yaml"; }

std::string tempPath(const std::string& name) { return testing::TempDir() + "climbsim_layout_" + name + ".yaml"; }

std::string errorOfText(const std::string& name, const std::string& text) {
  std::ofstream(tempPath(name)) << text;
  try {
    loadRobotDescription(tempPath(name));
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

/// Area and centroid of `polygon` by counting the centres of a fine square grid that fall
/// inside it (even-odd rule): independent of the shoelace formula the geometry uses.
struct Sampled {
  double area_m2 = 0.0;
  double cx_m = 0.0;
  double cy_m = 0.0;
};
Sampled sample(const std::vector<RobotGeometry::Point>& polygon, double step_m) {
  double x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9;
  for (const auto& p : polygon) {
    x0 = std::min(x0, p.x_m), x1 = std::max(x1, p.x_m), y0 = std::min(y0, p.y_m), y1 = std::max(y1, p.y_m);
  }
  Sampled s;
  for (double y = y0 + step_m / 2; y < y1; y += step_m) {
    for (double x = x0 + step_m / 2; x < x1; x += step_m) {
      bool inside = false;
      for (std::size_t k = 0, j = polygon.size() - 1; k < polygon.size(); j = k++) {
        const auto& a = polygon[k];
        const auto& b = polygon[j];
        if ((a.y_m > y) != (b.y_m > y) && x < (b.x_m - a.x_m) * (y - a.y_m) / (b.y_m - a.y_m) + a.x_m) inside = !inside;
      }
      if (!inside) continue;
      s.area_m2 += step_m * step_m;
      s.cx_m += x * step_m * step_m;
      s.cy_m += y * step_m * step_m;
    }
  }
  s.cx_m /= s.area_m2;
  s.cy_m /= s.area_m2;
  return s;
}

double totalLength(const RobotGeometry& g, RobotGeometry::SegmentKind kind) {
  double sum = 0.0;
  for (const auto& s : g.segments) {
    if (s.kind == kind) sum += s.length_m;
  }
  return sum;
}

TEST(RobotLayouts, EveryShippedRobotLoadsWithItsChambersWheelsAndAir) {
  struct Expect {
    const char* name;
    Layout layout;
    int chambers;
    bool reservoir;
    std::size_t wheels;
  };
  for (const Expect& e : {Expect{"cromsci", Layout::kRing, 7, true, 3}, Expect{"single-chamber", Layout::kSingle, 1, false, 3},
                          Expect{"grid-2x2", Layout::kGrid, 4, true, 4}, Expect{"ring-12", Layout::kRing, 13, true, 4}}) {
    SCOPED_TRACE(e.name);
    const RobotDescription d = loadRobotDescription(shippedFile(e.name));
    EXPECT_EQ(d.name, e.name);
    EXPECT_EQ(d.chambers.layout, e.layout);
    EXPECT_EQ(d.chambers.total(), e.chambers);
    EXPECT_EQ(d.reservoir.present, e.reservoir);
    EXPECT_EQ(d.wheels.size(), e.wheels);
    const RobotGeometry g = computeGeometry(d);
    EXPECT_EQ(g.chamberCount(), e.chambers);
    EXPECT_EQ(g.volumeCount(), e.chambers + (e.reservoir ? 1 : 0));
    // Every chamber is bounded by segments that close around it.
    for (const auto& c : g.chambers) EXPECT_FALSE(g.segmentsOf(c.id).empty()) << "chamber " << c.number;
    // Each chamber's area and centroid agree with sampling its outline on a 1 mm grid.
    for (const auto& c : g.chambers) {
      const Sampled s = sample(c.outline_Robot, 1e-3);
      EXPECT_NEAR(c.area_m2, s.area_m2, 2e-3 * c.area_m2) << "chamber " << c.number;
      EXPECT_NEAR(c.p_RobotCentroid.x_m, s.cx_m, 1e-3) << "chamber " << c.number;
      EXPECT_NEAR(c.p_RobotCentroid.y_m, s.cy_m, 1e-3) << "chamber " << c.number;
    }
  }
}

TEST(RobotLayouts, TheSingleChamberIsADiscWithOneOuterStripAndEnginesOnIt) {
  const RobotDescription d = loadRobotDescription(shippedFile("single-chamber"));
  const RobotGeometry g = computeGeometry(d);
  ASSERT_EQ(g.chamberCount(), 1);
  EXPECT_FALSE(g.has_reservoir);
  EXPECT_DOUBLE_EQ(g.chambers[0].area_m2, kPi * 0.25 * 0.25);
  ASSERT_EQ(g.segments.size(), 1u);
  EXPECT_EQ(g.segments[0].name, "outer1");
  EXPECT_EQ(g.segments[0].volume_b, kAmbient);
  EXPECT_NEAR(g.segments[0].length_m, kPi * 0.50, 1e-4 * kPi * 0.50);  // the sampled circle's perimeter
  EXPECT_EQ(d.engines.chambers, (std::vector<int>{1}));
  EXPECT_EQ(g.wheels[0].kind, Kind::kFixed);
  EXPECT_EQ(g.wheels[2].kind, Kind::kCaster);
  EXPECT_DOUBLE_EQ(g.wheels[2].radius_m, 0.025);
}

TEST(RobotLayouts, AGridHasLShapedOuterStripsAndWallsBetweenNeighbours) {
  const RobotDescription d = loadRobotDescription(shippedFile("grid-2x2"));
  const RobotGeometry g = computeGeometry(d);
  const double length = 0.64, width = 0.54;
  ASSERT_EQ(g.chamberCount(), 4);
  for (const auto& c : g.chambers) EXPECT_NEAR(c.area_m2, length * width / 4.0, 1e-15);
  EXPECT_NEAR(g.suctionArea(), length * width, 1e-15);
  // Chamber 1 at (-x, -y), numbered along x first.
  EXPECT_NEAR(g.chambers[0].p_RobotCentroid.x_m, -length / 4.0, 1e-15);
  EXPECT_NEAR(g.chambers[0].p_RobotCentroid.y_m, -width / 4.0, 1e-15);
  EXPECT_NEAR(g.chambers[1].p_RobotCentroid.x_m, length / 4.0, 1e-15);
  std::map<std::string, double> length_of;
  for (const auto& s : g.segments) length_of[s.name] = s.length_m;
  const std::map<std::string, double> expected = {
      {"outer1", (length + width) / 2.0}, {"outer2", (length + width) / 2.0}, {"outer3", (length + width) / 2.0},
      {"outer4", (length + width) / 2.0}, {"wall1_2", width / 2.0},          {"wall1_3", length / 2.0},
      {"wall2_4", length / 2.0},          {"wall3_4", width / 2.0}};
  ASSERT_EQ(length_of.size(), expected.size());
  for (const auto& [name, l] : expected) EXPECT_NEAR(length_of[name], l, 1e-12) << name;
  EXPECT_NEAR(totalLength(g, RobotGeometry::SegmentKind::kOuter), 2.0 * (length + width), 1e-12);
  // Every wall joins the two chambers its name says, and is symmetric in pairs.
  for (const auto& s : g.segments) {
    if (s.kind != RobotGeometry::SegmentKind::kWall) continue;
    EXPECT_EQ(s.name, "wall" + std::to_string(s.volume_a + 1) + "_" + std::to_string(s.volume_b + 1));
  }
}

TEST(RobotLayouts, ARingOfTwelveHasThreeStripsPerSectorAndItsCentre) {
  const RobotGeometry g = computeGeometry(loadRobotDescription(shippedFile("ring-12")));
  EXPECT_EQ(g.outer_count, 12);
  EXPECT_TRUE(g.has_centre);
  EXPECT_EQ(g.segments.size(), 36u);
  EXPECT_NEAR(g.suctionArea(), kPi * 0.46 * 0.46, 1e-12);
  EXPECT_NEAR(totalLength(g, RobotGeometry::SegmentKind::kOuter), 2.0 * kPi * 0.46, 1e-12);
  EXPECT_NEAR(totalLength(g, RobotGeometry::SegmentKind::kInner), 2.0 * kPi * 0.20, 1e-12);
  EXPECT_EQ(g.volumeName(g.centreChamber()), "13");
  EXPECT_EQ(g.volumeName(g.reservoir()), "R");
  EXPECT_NEAR(g.wheels[1].angle_rad, 3.0 * 2.0 * kPi / 12.0, 1e-12);
}

TEST(RobotLayouts, ARingWithoutACentreIsPieSlicesMeetingAtTheOrigin) {
  RobotDescription d = loadRobotDescription(shippedFile("cromsci"));
  d.chambers.centre_radius_m = 0.0;
  d.chambers.count = 4;
  d.wheels.resize(2);
  d.wheels[1].chamber = 3;
  validateRobotDescription(d, "test");
  const RobotGeometry g = computeGeometry(d);
  EXPECT_EQ(g.chamberCount(), 4);
  EXPECT_FALSE(g.has_centre);
  EXPECT_EQ(g.segments.size(), 8u);  // 4 outer arcs, 4 radial walls, no inner strip
  EXPECT_NEAR(g.suctionArea(), kPi * 0.36 * 0.36, 1e-12);
  for (const auto& c : g.chambers) {
    const Sampled s = sample(c.outline_Robot, 1e-3);
    EXPECT_NEAR(c.area_m2, s.area_m2, 2e-3 * c.area_m2);
    EXPECT_NEAR(c.p_RobotCentroid.x_m, s.cx_m, 1e-3);
    EXPECT_NEAR(c.p_RobotCentroid.y_m, s.cy_m, 1e-3);
  }
}

/// A polygons robot: an L of three 0.2 m squares (chambers 1 and 2 along x, 3 above 1).
std::string polygonsRobot(const std::string& chambers, const std::string& wheels =
                                                           "  - {kind: fixed, x_m: -0.1, y_m: -0.1, radius_m: 0.04, friction_coefficient: 0.7}\n") {
  return "name: ell\n"
         "body: {shape: rectangle, length_m: 0.5, width_m: 0.5, mass_kg: 10, com_height_m: 0.1}\n"
         "chambers:\n  layout: polygons\n  polygons:\n" +
         chambers +
         "sealing: {strip_width_m: 0.02, travel_m: 0.005, max_slope: 0.3, basic_gap_m: 1.0e-4, kappa_L: 1.0}\n"
         "engines: {count: 1, dp_max_pa: 20000, flow_max_m3ps: 0.03, speed_lag_s: 0.3, chambers: [1]}\n"
         "wheels:\n" +
         wheels +
         "drive: {max_speed_mps: 0.1, max_steering_rate_degps: 90}\n"
         "adhesion: {desired_downforce_n: 300}\n"
         "gas: {ambient_pressure_pa: 100000, temperature_k: 293.15, kappa: 1.402, r_air_jpkgk: 287.058, rho_kgpm3: "
         "1.1883}\n";
}

const char* kEll =
    "    - {outline_m: [[-0.2, -0.2], [0.0, -0.2], [0.0, 0.0], [-0.2, 0.0]], volume_m3: 1.0e-3}\n"
    "    - {outline_m: [[0.0, -0.2], [0.2, -0.2], [0.2, 0.0], [0.0, 0.0]], volume_m3: 1.0e-3}\n"
    "    - {outline_m: [[-0.2, 0.0], [0.0, 0.0], [0.0, 0.2], [-0.2, 0.2]], volume_m3: 1.0e-3}\n";

TEST(RobotLayouts, PolygonChambersSharingEdgesGetWallsAndOneOuterLoop) {
  ASSERT_EQ(errorOfText("ell", polygonsRobot(kEll)), "");
  const RobotGeometry g = computeGeometry(loadRobotDescription(tempPath("ell")));
  ASSERT_EQ(g.chamberCount(), 3);
  EXPECT_NEAR(g.suctionArea(), 3 * 0.04, 1e-15);
  std::set<std::string> names;
  for (const auto& s : g.segments) names.insert(s.name);
  EXPECT_EQ(names, (std::set<std::string>{"outer1", "outer2", "outer3", "wall1_2", "wall1_3"}));
  // The outer loop of the L: 8 sides of 0.2 m.
  EXPECT_NEAR(totalLength(g, RobotGeometry::SegmentKind::kOuter), 8 * 0.2, 1e-12);
  // A clockwise outline is the same chamber.
  const std::string clockwise =
      "    - {outline_m: [[-0.2, 0.0], [0.0, 0.0], [0.0, -0.2], [-0.2, -0.2]], volume_m3: 1.0e-3}\n"
      "    - {outline_m: [[0.0, -0.2], [0.2, -0.2], [0.2, 0.0], [0.0, 0.0]], volume_m3: 1.0e-3}\n"
      "    - {outline_m: [[-0.2, 0.0], [0.0, 0.0], [0.0, 0.2], [-0.2, 0.2]], volume_m3: 1.0e-3}\n";
  ASSERT_EQ(errorOfText("ell_cw", polygonsRobot(clockwise)), "");
  EXPECT_NEAR(computeGeometry(loadRobotDescription(tempPath("ell_cw"))).chambers[0].area_m2, 0.04, 1e-15);
}

/// One line naming the file and line, the key and value, and why.
void expectLine(const std::string& message, const std::string& name, const std::string& key_value,
                const std::string& why) {
  SCOPED_TRACE(message);
  EXPECT_EQ(message.rfind(tempPath(name) + ":", 0), 0u);
  EXPECT_NE(message.find(key_value), std::string::npos);
  EXPECT_NE(message.find(why), std::string::npos);
  EXPECT_EQ(message.find('\n'), std::string::npos);
}

TEST(RobotLayouts, OverlappingOutsideAndUnclosedChambersAreOneLineEach) {
  const std::string overlapping =
      "    - {outline_m: [[-0.2, -0.2], [0.0, -0.2], [0.0, 0.0], [-0.2, 0.0]], volume_m3: 1.0e-3}\n"
      "    - {outline_m: [[-0.1, -0.1], [0.1, -0.1], [0.1, 0.1], [-0.1, 0.1]], volume_m3: 1.0e-3}\n";
  expectLine(errorOfText("overlap", polygonsRobot(overlapping)), "overlap", "chambers.polygons[2].outline_m",
             "overlaps chamber 1");
  const std::string outside =
      "    - {outline_m: [[-0.2, -0.2], [0.3, -0.2], [0.3, 0.0], [-0.2, 0.0]], volume_m3: 1.0e-3}\n";
  expectLine(errorOfText("outside", polygonsRobot(outside)), "outside", "chambers.polygons[1].outline_m",
             "reaches outside the body (body 0.5 m x 0.5 m) at (0.3, -0.2)");
  const std::string apart =
      "    - {outline_m: [[-0.2, -0.2], [-0.05, -0.2], [-0.05, 0.0], [-0.2, 0.0]], volume_m3: 1.0e-3}\n"
      "    - {outline_m: [[0.05, -0.2], [0.2, -0.2], [0.2, 0.0], [0.05, 0.0]], volume_m3: 1.0e-3}\n";
  expectLine(errorOfText("apart", polygonsRobot(apart)), "apart", "chambers.polygons",
             "the outer sealing strip does not close into one loop");
  const std::string t_joint =
      "    - {outline_m: [[-0.2, -0.2], [0.2, -0.2], [0.2, 0.0], [-0.2, 0.0]], volume_m3: 1.0e-3}\n"
      "    - {outline_m: [[-0.2, 0.0], [0.0, 0.0], [0.0, 0.2], [-0.2, 0.2]], volume_m3: 1.0e-3}\n";
  const std::string t_message = errorOfText("tjoint", polygonsRobot(t_joint));
  EXPECT_NE(t_message.find("without the same corners"), std::string::npos) << t_message;
  const std::string bow_tie = "    - {outline_m: [[-0.2, -0.2], [0.2, 0.2], [0.2, -0.2], [-0.2, 0.2]], volume_m3: 1.0e-3}\n";
  expectLine(errorOfText("bowtie", polygonsRobot(bow_tie)), "bowtie", "chambers.polygons[1].outline_m",
             "crosses itself");
}

TEST(RobotLayouts, WheelsOutsideTheBodyOrOnAStripAreRefused) {
  expectLine(errorOfText("wheel_out", polygonsRobot(kEll, "  - {kind: fixed, x_m: 0.3, y_m: 0.0, radius_m: 0.04, "
                                                          "friction_coefficient: 0.7}\n")),
             "wheel_out", "wheels[1].x_m = 0.3", "outside the body");
  expectLine(errorOfText("wheel_strip", polygonsRobot(kEll, "  - {kind: caster, x_m: 0.0, y_m: -0.1, radius_m: 0.04, "
                                                            "friction_coefficient: 0.7}\n  - {kind: fixed, x_m: -0.1, "
                                                            "y_m: -0.1, radius_m: 0.04, friction_coefficient: 0.7}\n")),
             "wheel_strip", "wheels[1].x_m = 0.0", "lies on the sealing strip wall1_2");
  std::string kinds = polygonsRobot(kEll, "  - {kind: skate, x_m: -0.1, y_m: -0.1, radius_m: 0.04, friction_coefficient: 0.7}\n");
  expectLine(errorOfText("kind", kinds), "kind", "wheels[1].kind = skate", "must be one of steerable, fixed, caster");
}

TEST(RobotLayouts, CountsBeyondTheirMaximaAreRefused) {
  std::string wheels;
  for (int i = 0; i < kMaxWheels + 1; ++i) {
    wheels += "  - {kind: fixed, x_m: -0.1, y_m: -0.1, radius_m: 0.04, friction_coefficient: 0.7}\n";
  }
  expectLine(errorOfText("nine", polygonsRobot(kEll, wheels)), "nine", "wheels = ", "must list 1..8 wheels");
  std::string ring = "name: r\nbody: {diameter_m: 2.0, mass_kg: 10, com_height_m: 0.1}\n"
                     "chambers: {layout: ring, count: 30, sealed_diameter_m: 1.8, volume_m3: 1e-3}\n";
  const std::string message = errorOfText("ring30", ring);
  EXPECT_NE(message.find("chambers.count = 30: must be an integer in 3..24"), std::string::npos) << message;
  const std::string grid = "name: g\nbody: {shape: rectangle, length_m: 2, width_m: 2, mass_kg: 10, com_height_m: 0.1}\n"
                           "chambers: {layout: grid, rows: 5, columns: 5, length_m: 1, width_m: 1, volume_m3: 1e-3}\n";
  EXPECT_NE(errorOfText("grid25", grid).find("rows x columns = 25 chambers, more than 24"), std::string::npos);
}

TEST(RobotLayouts, EnginesAndValvesMustFitTheReservoirOrItsAbsence) {
  const RobotDescription cromsci = loadRobotDescription(shippedFile("cromsci"));
  RobotDescription d = cromsci;
  d.reservoir.present = false;
  try {
    validateRobotDescription(d, "test");
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("engines.chambers = []: without a reservoir, name the chamber of each of the 3"),
              std::string::npos)
        << e.what();
  }
  d.engines.chambers = {1, 7, 9};
  try {
    validateRobotDescription(d, "test");
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("chamber 9 is not a chamber 1..7"), std::string::npos) << e.what();
  }
  std::ifstream in(shippedFile("single-chamber"));
  std::stringstream text;
  text << in.rdbuf();
  const std::string with_valves =
      text.str() + "valves: {max_area_m2: 7.0e-4, discharge_coefficient: 0.6, full_stroke_s: 0.2, command_delay_s: 0.02}\n";
  expectLine(errorOfText("valves", with_valves), "valves", "valves", "a robot without a reservoir has no valves");
}

TEST(RobotLayouts, EveryProblemOfAFileIsListedAtOnce) {
  const std::string message = errorOfText(
      "many", polygonsRobot(kEll, "  - {kind: skate, x_m: 0.3, y_m: 0.0, radius_m: -1, friction_coefficient: 0.7}\n"
                                  "  - {kind: fixed, x_m: -0.1, y_m: -0.1, radius_m: 0.04, friction_coefficient: 70}\n"));
  std::istringstream lines(message);
  int count = 0;
  for (std::string line; std::getline(lines, line);) {
    EXPECT_EQ(line.rfind(tempPath("many") + ":", 0), 0u) << line;
    ++count;
  }
  EXPECT_EQ(count, 3) << message;  // the kind, the radius, the friction
  EXPECT_NE(message.find("wheels[1].kind = skate"), std::string::npos) << message;
  EXPECT_NE(message.find("wheels[1].radius_m = -1"), std::string::npos) << message;
  EXPECT_NE(message.find("wheels[2].friction_coefficient = 70"), std::string::npos) << message;
}

}  // namespace
}  // namespace climbsim
