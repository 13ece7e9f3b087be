// Facts about the robot description and its geometry. Expected values come from
// docs/robot-files.md#default-values or from independent computations (numeric integration, polygon formulas), never from
// the formulas under test.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <sstream>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <set>

#include "climbsim/errors.hpp"
#include "climbsim/robot/robot_description.hpp"
#include "climbsim/robot/robot_geometry.hpp"

namespace climbsim {
namespace {

constexpr double kPi = 3.14159265358979323846;
const std::string kShipped = std::string(CLIMBSIM_ROBOTS_DIR) + "/cromsci.yaml";

using Point = RobotGeometry::Point;

const RobotDescription& shipped() {
  static const RobotDescription d = loadRobotDescription(kShipped);
  return d;
}

const RobotGeometry& geometry() {
  static const RobotGeometry g = computeGeometry(shipped());
  return g;
}

double wrapAngle(double a) { return std::remainder(a, 2.0 * kPi); }

// ---- description ----

TEST(RobotDescription, ShippedFileHoldsTheDesignDefaults) {
  const RobotDescription& d = shipped();
  EXPECT_EQ(d.name, "cromsci");
  EXPECT_DOUBLE_EQ(d.body.diameter_m, 0.80);
  EXPECT_EQ(d.body.shape, RobotDescription::Shape::kCircle);
  EXPECT_EQ(d.chambers.layout, RobotDescription::Layout::kRing);
  EXPECT_DOUBLE_EQ(d.chambers.sealed_diameter_m, 0.72);
  EXPECT_DOUBLE_EQ(d.body.mass_kg, 45.0);
  EXPECT_DOUBLE_EQ(d.body.com_height_m, 0.15);
  EXPECT_DOUBLE_EQ(d.chambers.centre_radius_m, 0.15);
  EXPECT_EQ(d.chambers.count, 6);
  EXPECT_EQ(d.chambers.total(), 7);
  EXPECT_DOUBLE_EQ(d.chambers.volume_m3, 2.2e-3);
  EXPECT_DOUBLE_EQ(d.chambers.centre_volume_m3, 2.8e-3);
  EXPECT_TRUE(d.reservoir.present);
  EXPECT_DOUBLE_EQ(d.reservoir.volume_m3, 15e-3);
  EXPECT_DOUBLE_EQ(d.sealing.strip_width_m, 0.02);
  EXPECT_DOUBLE_EQ(d.sealing.travel_m, 0.005);
  EXPECT_DOUBLE_EQ(d.sealing.max_slope, 0.3);
  EXPECT_DOUBLE_EQ(d.sealing.basic_gap_m, 1e-4);
  EXPECT_DOUBLE_EQ(d.sealing.kappa_L, 1.0);
  EXPECT_EQ(d.engines.count, 3);
  EXPECT_DOUBLE_EQ(d.engines.dp_max_pa, 22000.0);
  EXPECT_DOUBLE_EQ(d.engines.flow_max_m3ps, 0.040);
  EXPECT_DOUBLE_EQ(d.engines.speed_lag_s, 0.5);
  EXPECT_DOUBLE_EQ(d.valves.max_area_m2, 7e-4);
  EXPECT_DOUBLE_EQ(d.valves.discharge_coefficient, 0.6);
  EXPECT_DOUBLE_EQ(d.valves.full_stroke_s, 0.2);
  EXPECT_DOUBLE_EQ(d.valves.command_delay_s, 0.02);
  ASSERT_EQ(d.wheels.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(d.wheels[i].kind, RobotDescription::WheelKind::kSteerable);
    EXPECT_EQ(d.wheels[i].chamber, static_cast<int>(2 * i + 1));
    EXPECT_DOUBLE_EQ(d.wheels[i].mount_radius_m, 0.26);
    EXPECT_DOUBLE_EQ(d.wheels[i].radius_m, 0.05);
    EXPECT_DOUBLE_EQ(d.wheels[i].friction_coefficient, 0.7);
  }
  EXPECT_DOUBLE_EQ(d.drive.max_speed_mps, 0.1);
  EXPECT_DOUBLE_EQ(d.drive.max_steering_rate_radps, kPi / 2.0);
  EXPECT_DOUBLE_EQ(d.adhesion.desired_downforce_n, 2200.0);
  EXPECT_DOUBLE_EQ(d.gas.ambient_pressure_pa, 100000.0);
  EXPECT_DOUBLE_EQ(d.gas.temperature_k, 293.15);
  EXPECT_DOUBLE_EQ(d.gas.kappa, 1.402);
  EXPECT_DOUBLE_EQ(d.gas.r_air_jpkgk, 287.058);
  EXPECT_DOUBLE_EQ(d.gas.rho_kgpm3, 1.1883);
}

std::string tempPath(const std::string& name) { return testing::TempDir() + "climbsim_robot_" + name + ".yaml"; }

/// The ConfigError message of loading `text` from a temporary file ("" if it loaded).
std::string errorOfText(const std::string& name, const std::string& text) {
  const std::string path = tempPath(name);
  std::ofstream(path) << text;
  try {
    loadRobotDescription(path);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

/// The shipped file, changed by `edit`, loaded from a temporary file.
template <typename Edit>
std::string errorOfEdit(const std::string& name, Edit edit) {
  YAML::Node doc = YAML::LoadFile(kShipped);
  edit(doc);
  YAML::Emitter out;
  out << doc;
  return errorOfText(name, out.c_str());
}

/// The message is one line naming the file, then `key = value`, then `why`.
void expectNames(const std::string& message, const std::string& name, const std::string& key_value,
                 const std::string& why) {
  SCOPED_TRACE(message);
  EXPECT_EQ(message.rfind(tempPath(name) + ":", 0), 0u) << "does not start with the file name";
  EXPECT_NE(message.find(key_value), std::string::npos);
  EXPECT_NE(message.find(why), std::string::npos);
  EXPECT_EQ(message.find('\n'), std::string::npos);
}

TEST(RobotDescription, NegativeOrZeroVolumeNamesFileKeyAndValue) {
  expectNames(errorOfEdit("neg", [](YAML::Node& d) { d["chambers"]["volume_m3"] = "-1"; }), "neg",
              "chambers.volume_m3 = -1", "must be in (0, 10]");
  expectNames(errorOfEdit("zero", [](YAML::Node& d) { d["reservoir"]["volume_m3"] = "0"; }), "zero",
              "reservoir.volume_m3 = 0", "must be in (0, 100]");
  // Every number has a physical range: a typo of many orders of magnitude is refused.
  expectNames(errorOfEdit("travel", [](YAML::Node& d) { d["sealing"]["travel_m"] = "9.9e99"; }), "travel",
              "sealing.travel_m = 9.9e99", "must be in (0, 0.5]");
}

TEST(RobotDescription, NonNumbersAndNonFiniteValuesAreRejected) {
  expectNames(errorOfEdit("text", [](YAML::Node& d) { d["gas"]["kappa"] = "fast"; }), "text", "gas.kappa = fast",
              "must be a finite number");
  expectNames(errorOfEdit("nan", [](YAML::Node& d) { d["valves"]["max_area_m2"] = ".nan"; }), "nan",
              "valves.max_area_m2 = .nan", "finite");
  expectNames(errorOfEdit("int", [](YAML::Node& d) { d["chambers"]["count"] = "6.5"; }), "int",
              "chambers.count = 6.5", "integer");
}

// sealing.channel_bound: optional (absent in the shipped file: off), true or false, read with
// YamlFields; a bad value is one line with the file, its line, the key and the value.
TEST(RobotDescription, ChannelBoundIsAnOptionalBooleanNamedWithItsLineWhenBad) {
  EXPECT_FALSE(shipped().sealing.channel_bound);
  YAML::Node doc = YAML::LoadFile(kShipped);
  doc["sealing"]["channel_bound"] = true;
  YAML::Emitter out;
  out << doc;
  const std::string on = tempPath("channel_bound_on");
  std::ofstream(on) << out.c_str();
  EXPECT_TRUE(loadRobotDescription(on).sealing.channel_bound);

  const std::string text = std::string(out.c_str());
  std::string bad = text;
  const std::string key = "channel_bound: true";
  const auto at = bad.find(key);
  ASSERT_NE(at, std::string::npos) << text;
  bad.replace(at, key.size(), "channel_bound: maybe");
  const int line = static_cast<int>(std::count(bad.begin(), bad.begin() + static_cast<long>(at), '\n')) + 1;
  const std::string message = errorOfText("channel_bound_bad", bad);
  expectNames(message, "channel_bound_bad", "sealing.channel_bound = maybe", "true or false");
  EXPECT_EQ(message.rfind(tempPath("channel_bound_bad") + ":" + std::to_string(line) + ":", 0), 0u) << message;
}

TEST(RobotDescription, UnknownKeysAreErrors) {
  const std::string typo = errorOfEdit("typo", [](YAML::Node& d) {
    d["chambers"].remove("volume_m3");
    d["chambers"]["volum_m3"] = "2.2e-3";
  });
  expectNames(typo, "typo", "chambers.volum_m3", "unknown key");
  EXPECT_NE(typo.find("volume_m3"), std::string::npos) << "should list the known keys: " << typo;
  expectNames(errorOfEdit("section", [](YAML::Node& d) { d["wheel"]["radius_m"] = "0.05"; }), "section", "wheel",
              "unknown key");
}

TEST(RobotDescription, MissingKeysAreErrors) {
  expectNames(errorOfEdit("missing", [](YAML::Node& d) { d["gas"].remove("kappa"); }), "missing", "gas.kappa",
              "missing");
  expectNames(errorOfEdit("nosection", [](YAML::Node& d) { d.remove("valves"); }), "nosection", "valves",
              "missing");
}

TEST(RobotDescription, EveryProblemOfAFileIsReportedInLineOrder) {
  const std::string message = errorOfEdit("many", [](YAML::Node& d) {
    d["gas"]["kappa"] = "fast";
    d["body"]["mass_kg"] = "-45";
    d["valves"]["full_stroke_s"] = "1e308";
  });
  std::vector<int> lines;
  std::istringstream in(message);
  for (std::string line; std::getline(in, line);) {
    EXPECT_EQ(line.rfind(tempPath("many") + ":", 0), 0u) << line;
    lines.push_back(std::atoi(line.c_str() + tempPath("many").size() + 1));
  }
  ASSERT_EQ(lines.size(), 3u) << message;
  EXPECT_TRUE(std::is_sorted(lines.begin(), lines.end())) << message;
  EXPECT_NE(message.find("body.mass_kg = -45"), std::string::npos) << message;
  EXPECT_NE(message.find("valves.full_stroke_s = 1e308"), std::string::npos) << message;
  EXPECT_NE(message.find("gas.kappa = fast"), std::string::npos) << message;
}

TEST(RobotDescription, StructureProblemsAreReportedWithTheValuesOnesInLineOrder) {
  // A section that is no mapping, a typo (whose missing key is then not reported twice), a
  // missing key and a bad value: one line each, from YamlFields, sorted by line.
  const std::string message = errorOfEdit("structure", [](YAML::Node& d) {
    d["reservoir"] = "big";
    d["wheels"][0].remove("radius_m");
    d["wheels"][0]["radius_mm"] = "50";
    d["gas"].remove("kappa");
    d["body"]["mass_kg"] = "heavy";
  });
  std::vector<int> lines;
  std::istringstream in(message);
  for (std::string line; std::getline(in, line);) {
    EXPECT_EQ(line.rfind(tempPath("structure") + ":", 0), 0u) << line;
    lines.push_back(std::atoi(line.c_str() + tempPath("structure").size() + 1));
  }
  ASSERT_EQ(lines.size(), 4u) << message;
  EXPECT_TRUE(std::is_sorted(lines.begin(), lines.end())) << message;
  EXPECT_NE(message.find("body.mass_kg = heavy: it must be a finite number"), std::string::npos) << message;
  EXPECT_NE(message.find("reservoir = big: it must be a mapping"), std::string::npos) << message;
  EXPECT_NE(message.find("wheels[1].radius_mm: unknown key (known keys: kind, chamber, mount_radius_m, radius_m,"),
            std::string::npos)
      << message;
  EXPECT_EQ(message.find("wheels[1].radius_m: missing"), std::string::npos) << message;
  EXPECT_NE(message.find("gas.kappa: missing"), std::string::npos) << message;
}

TEST(RobotDescription, DuplicateKeysAndBrokenFilesAreErrors) {
  const std::string dup = errorOfText("dup", "name: a\nname: b\n");
  EXPECT_NE(dup.find("name"), std::string::npos) << dup;
  EXPECT_NE(dup.find("duplicate"), std::string::npos) << dup;
  EXPECT_NE(errorOfText("broken", "name: [a\n").find("YAML syntax error"), std::string::npos);
  EXPECT_NE(errorOfText("list", "- 1\n- 2\n").find("mapping"), std::string::npos);
  EXPECT_THROW(loadRobotDescription(tempPath("does_not_exist")), ConfigError);
}

TEST(RobotDescription, GeometricInconsistenciesAreErrors) {
  expectNames(errorOfEdit("centre", [](YAML::Node& d) { d["chambers"]["centre_radius_m"] = "0.4"; }), "centre",
              "chambers.centre_radius_m = 0.4", "must be <");
  expectNames(errorOfEdit("sealed", [](YAML::Node& d) { d["chambers"]["sealed_diameter_m"] = "0.8"; }), "sealed",
              "chambers.sealed_diameter_m = ", "reaches outside the body (body.diameter_m = 0.8)");
  expectNames(errorOfEdit("mount", [](YAML::Node& d) { d["wheels"][1]["mount_radius_m"] = "0.15"; }), "mount",
              "wheels[2].mount_radius_m = 0.15", "lies on the sealing strip inner3");
  expectNames(errorOfEdit("wheel7", [](YAML::Node& d) { d["wheels"][2]["chamber"] = "7"; }), "wheel7",
              "wheels[3].chamber = 7", "must be a ring chamber 1..6");
  expectNames(errorOfEdit("force", [](YAML::Node& d) { d["adhesion"]["desired_downforce_n"] = "20000"; }), "force",
              "adhesion.desired_downforce_n = 20000", "cannot reach");
  expectNames(errorOfEdit("rho", [](YAML::Node& d) { d["gas"]["rho_kgpm3"] = "11.883"; }), "rho",
              "gas.rho_kgpm3 = 11.883", "within 10 %");
  expectNames(errorOfEdit("cd", [](YAML::Node& d) { d["valves"]["discharge_coefficient"] = "1.5"; }), "cd",
              "valves.discharge_coefficient = 1.5", "(0, 1]");
}

TEST(RobotDescription, ValidateChecksDescriptionsBuiltInCode) {
  EXPECT_NO_THROW(validateRobotDescription(shipped(), "test"));
  EXPECT_THROW(validateRobotDescription(RobotDescription{}, "test"), ConfigError);
  RobotDescription d = shipped();
  d.chambers.volume_m3 = -1.0;
  try {
    validateRobotDescription(d, "scenario --set");
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(), "scenario --set: chambers.volume_m3 = -1: must be in (0, 10]");
  }
}

// ---- geometry ----

double shoelaceArea(const std::vector<Point>& poly) {
  double twice = 0.0;
  for (std::size_t k = 0; k < poly.size(); ++k) {
    const Point& a = poly[k];
    const Point& b = poly[(k + 1) % poly.size()];
    twice += a.x_m * b.y_m - b.x_m * a.y_m;
  }
  return twice / 2.0;
}

bool insidePolygon(const std::vector<Point>& poly, Point p) {
  bool inside = false;
  for (std::size_t k = 0, j = poly.size() - 1; k < poly.size(); j = k++) {
    const Point& a = poly[k];
    const Point& b = poly[j];
    if ((a.y_m > p.y_m) != (b.y_m > p.y_m) &&
        p.x_m < (b.x_m - a.x_m) * (p.y_m - a.y_m) / (b.y_m - a.y_m) + a.x_m) {
      inside = !inside;
    }
  }
  return inside;
}

double polylineLength(const std::vector<Point>& line) {
  double sum_m = 0.0;
  for (std::size_t k = 1; k < line.size(); ++k) {
    sum_m += std::hypot(line[k].x_m - line[k - 1].x_m, line[k].y_m - line[k - 1].y_m);
  }
  return sum_m;
}

TEST(RobotGeometry, SuctionAreasFillTheSealedDisc) {
  const RobotGeometry& g = geometry();
  ASSERT_EQ(g.chambers.size(), 7u);
  EXPECT_NEAR(g.suctionArea(), kPi * 0.36 * 0.36, 1e-12);
  EXPECT_NEAR(g.chambers[g.centreChamber()].area_m2, kPi * 0.15 * 0.15, 1e-12);
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(g.chambers[i].area_m2, kPi * (0.36 * 0.36 - 0.15 * 0.15) / 6.0, 1e-12);
}

TEST(RobotGeometry, CentroidOfTheUnionIsTheCentre) {
  double x = 0.0;
  double y = 0.0;
  for (const auto& c : geometry().chambers) {
    x += c.area_m2 * c.p_RobotCentroid.x_m;
    y += c.area_m2 * c.p_RobotCentroid.y_m;
  }
  EXPECT_NEAR(x / geometry().suctionArea(), 0.0, 1e-15);
  EXPECT_NEAR(y / geometry().suctionArea(), 0.0, 1e-15);
}

TEST(RobotGeometry, SectorAreaAndCentroidMatchNumericIntegration) {
  constexpr int kCells = 500;
  for (int i = 0; i < 6; ++i) {
    const auto& c = geometry().chambers[i];
    EXPECT_EQ(c.number, i + 1);
    EXPECT_NEAR(wrapAngle(c.centre_angle_rad - i * kPi / 3.0), 0.0, 1e-12) << "counter-clockwise, 1 on +x";
    // Midpoint rule over a polar grid of the 60° sector 0.15..0.36 m: dA = r dr dphi.
    const double from_rad = i * kPi / 3.0 - kPi / 6.0;
    const double dr = (0.36 - 0.15) / kCells;
    const double dphi = (kPi / 3.0) / kCells;
    double area = 0.0;
    double mx = 0.0;
    double my = 0.0;
    for (int a = 0; a < kCells; ++a) {
      const double r = 0.15 + (a + 0.5) * dr;
      for (int b = 0; b < kCells; ++b) {
        const double phi = from_rad + (b + 0.5) * dphi;
        const double dA = r * dr * dphi;
        area += dA;
        mx += r * std::cos(phi) * dA;
        my += r * std::sin(phi) * dA;
      }
    }
    EXPECT_NEAR(c.area_m2, area, 1e-9);
    EXPECT_NEAR(c.p_RobotCentroid.x_m, mx / area, 1e-6);
    EXPECT_NEAR(c.p_RobotCentroid.y_m, my / area, 1e-6);
    EXPECT_NEAR(std::hypot(c.p_RobotCentroid.x_m, c.p_RobotCentroid.y_m), std::hypot(mx, my) / area, 1e-6);
  }
  const auto& centre = geometry().chambers[6];
  EXPECT_EQ(centre.number, 7);
  EXPECT_EQ(centre.p_RobotCentroid.x_m, 0.0);
  EXPECT_EQ(centre.p_RobotCentroid.y_m, 0.0);
}

TEST(RobotGeometry, OutlinesAreCounterClockwisePolygonsOfTheSuctionAreas) {
  for (const auto& c : geometry().chambers) {
    SCOPED_TRACE(c.number);
    const double area = shoelaceArea(c.outline_Robot);
    EXPECT_GT(area, 0.0);
    EXPECT_NEAR(area / c.area_m2, 1.0, 1e-4);
    EXPECT_TRUE(insidePolygon(c.outline_Robot, c.p_RobotCentroid));
  }
}

TEST(RobotGeometry, EighteenSegmentsWithTheRightLengths) {
  const RobotGeometry& g = geometry();
  ASSERT_EQ(g.segments.size(), 18u);
  double outer = 0.0;
  double inner = 0.0;
  double radial = 0.0;
  std::set<std::string> names;
  for (const auto& s : g.segments) {
    names.insert(s.name);
    EXPECT_NEAR(polylineLength(s.centreline_Robot) / s.length_m, 1.0, 1e-4) << s.name;
    (s.kind == RobotGeometry::SegmentKind::kOuter    ? outer
     : s.kind == RobotGeometry::SegmentKind::kInner ? inner
                                                     : radial) += s.length_m;
  }
  EXPECT_EQ(names.size(), 18u);
  for (const char* n : {"outer1", "outer6", "radial1_2", "radial6_1", "inner1", "inner6"}) {
    EXPECT_EQ(names.count(n), 1u) << n;
  }
  EXPECT_NEAR(outer, 2.0 * kPi * 0.36, 1e-12);
  EXPECT_NEAR(inner, 2.0 * kPi * 0.15, 1e-12);
  EXPECT_NEAR(radial, 6.0 * (0.36 - 0.15), 1e-12);
}

TEST(RobotGeometry, EachChamberIsBoundedByItsSegments) {
  using Kind = RobotGeometry::SegmentKind;
  const RobotGeometry& g = geometry();
  for (VolumeId id = 0; id < 6; ++id) {
    const auto found = g.segmentsOf(id);
    ASSERT_EQ(found.size(), 4u) << "chamber " << id + 1;
    std::multiset<Kind> kinds;
    std::set<VolumeId> others;
    for (const std::size_t s : found) {
      kinds.insert(g.segments[s].kind);
      others.insert(g.segments[s].volume_a == id ? g.segments[s].volume_b : g.segments[s].volume_a);
    }
    EXPECT_EQ(kinds.count(Kind::kOuter), 1u);
    EXPECT_EQ(kinds.count(Kind::kRadial), 2u);
    EXPECT_EQ(kinds.count(Kind::kInner), 1u);
    // Neighbours are cyclic: chamber 1 borders 6 and 2.
    EXPECT_EQ(others, (std::set<VolumeId>{kAmbient, (id + 5) % 6, (id + 1) % 6, g.centreChamber()}));
  }
  EXPECT_EQ(g.segmentsOf(g.centreChamber()).size(), 6u);
  EXPECT_EQ(g.segmentsOf(kAmbient).size(), 6u);
  EXPECT_TRUE(g.segmentsOf(g.reservoir()).empty());
}

TEST(RobotGeometry, SegmentCentreLinesLieOnTheChamberBoundaries) {
  const RobotGeometry& g = geometry();
  for (const auto& s : g.segments) {
    SCOPED_TRACE(s.name);
    for (const Point& p : s.centreline_Robot) {
      const double r = std::hypot(p.x_m, p.y_m);
      const double phi = std::atan2(p.y_m, p.x_m);
      const auto& a = g.chambers[s.volume_a];
      if (s.kind == RobotGeometry::SegmentKind::kOuter) {
        EXPECT_NEAR(r, 0.36, 1e-12);
      }
      if (s.kind == RobotGeometry::SegmentKind::kInner) {
        EXPECT_NEAR(r, 0.15, 1e-12);
      }
      if (s.kind == RobotGeometry::SegmentKind::kRadial) {
        EXPECT_NEAR(wrapAngle(phi - a.centre_angle_rad - kPi / 6.0), 0.0, 1e-12);
        EXPECT_NEAR(wrapAngle(phi - g.chambers[s.volume_b].centre_angle_rad + kPi / 6.0), 0.0, 1e-12);
      } else {
        EXPECT_LE(std::abs(wrapAngle(phi - a.centre_angle_rad)), kPi / 6.0 + 1e-12);
      }
    }
  }
}

TEST(RobotGeometry, WheelsAre120DegreesApartInChambers135) {
  const auto& wheels = geometry().wheels;
  ASSERT_EQ(wheels.size(), 3u);
  EXPECT_NEAR(wheels[0].p_RobotWheel.x_m, 0.26, 1e-15);
  EXPECT_NEAR(wheels[0].p_RobotWheel.y_m, 0.0, 1e-15);
  for (std::size_t k = 0; k < 3; ++k) {
    const Point p = wheels[k].p_RobotWheel;
    const Point q = wheels[(k + 1) % 3].p_RobotWheel;
    EXPECT_NEAR(std::hypot(p.x_m, p.y_m), 0.26, 1e-12);
    EXPECT_NEAR(wrapAngle(std::atan2(q.y_m, q.x_m) - std::atan2(p.y_m, p.x_m)), 2.0 * kPi / 3.0, 1e-12);
    EXPECT_EQ(wheels[k].chamber_number, static_cast<int>(2 * k + 1));
    EXPECT_TRUE(insidePolygon(geometry().chambers[wheels[k].chamber_number - 1].outline_Robot, p));
  }
}

TEST(RobotGeometry, VolumesAreNamedAndSizedAsInTheDesign) {
  const RobotGeometry& g = geometry();
  EXPECT_EQ(g.volumeCount(), 8);
  EXPECT_EQ(g.centreChamber(), 6);
  EXPECT_EQ(g.reservoir(), 7);
  EXPECT_EQ(g.volumeName(0), "1");
  EXPECT_EQ(g.volumeName(6), "7");
  EXPECT_EQ(g.volumeName(7), "R");
  EXPECT_EQ(g.volumeName(kAmbient), "o");
  EXPECT_DOUBLE_EQ(g.volumeOf(0), 2.2e-3);
  EXPECT_DOUBLE_EQ(g.volumeOf(6), 2.8e-3);
  EXPECT_DOUBLE_EQ(g.volumeOf(7), 15e-3);
  EXPECT_THROW(g.volumeOf(kAmbient), std::out_of_range);
}

TEST(RobotGeometry, OtherChamberCountsFollowFromTheDescription) {
  RobotDescription d = shipped();
  d.chambers.count = 8;
  d.wheels[1].chamber = 4;
  d.wheels[2].chamber = 6;
  validateRobotDescription(d, "test");
  const RobotGeometry g = computeGeometry(d);
  EXPECT_EQ(g.segments.size(), 24u);
  EXPECT_EQ(g.segments[15].name, "radial8_1");
  EXPECT_NEAR(g.suctionArea(), kPi * 0.36 * 0.36, 1e-12);
  EXPECT_EQ(g.segmentsOf(g.centreChamber()).size(), 8u);
  EXPECT_EQ(g.volumeName(g.reservoir()), "R");
  EXPECT_EQ(g.volumeName(g.centreChamber()), "9");
}

}  // namespace
}  // namespace climbsim
