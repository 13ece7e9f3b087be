#include "climbsim/robot/robot_description.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "climbsim/errors.hpp"
#include "climbsim/robot/chamber_polygons.hpp"
#include "climbsim/robot/robot_geometry.hpp"
#include "climbsim/yaml_fields.hpp"

namespace climbsim {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegToRad = kPi / 180.0;
/// Relative tolerance of rho against the ideal gas law: wide enough for deliberate choices
/// (e.g. a density at chamber pressure), narrow enough to catch a misplaced decimal point.
constexpr double kRhoTolerance = 0.10;

using D = RobotDescription;

std::string show(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

std::string show(const std::vector<int>& values) {
  std::string out = "[";
  for (std::size_t i = 0; i < values.size(); ++i) out += (i == 0 ? "" : ", ") + std::to_string(values[i]);
  return out + "]";
}

std::string wheelKey(std::size_t i, const std::string& name) { return "wheels[" + std::to_string(i + 1) + "]." + name; }
std::string polygonKey(std::size_t i, const std::string& name) {
  return "chambers.polygons[" + std::to_string(i + 1) + "]." + name;
}

/// Records problems through YamlFields: "<file>:<line>: <key> = <value>: <why>" when the key
/// was read from a file (its node is known), else "<source>: <key> = <value>: <why>".
class Problems {
 public:
  explicit Problems(const YamlFields& fields) : fields_(fields) {}

  void node(const std::string& key, const YAML::Node& node) { nodes_[key].reset(node); }
  /// `key` is missing or did not read (already reported): checks of its value are skipped.
  void unread(const std::string& key) { unread_.insert(key); }
  void add(const std::string& key, const std::string& value, const std::string& why) const {
    if (isUnread(key)) return;
    fields_.check([&] {
      const auto it = nodes_.find(key);
      if (it != nodes_.end()) fields_.fail(it->second, key, why);
      fields_.failValue(0, key, value, why);
    });
  }
  void add(const std::string& key, double value, const std::string& why) const { add(key, show(value), why); }

  /// Range rules of a number in the file's units (the physical upper bound catches typos).
  void positive(const std::string& key, double v, double max) const {
    if (!(std::isfinite(v) && v > 0.0 && v <= max)) add(key, v, "must be in (0, " + show(max) + "]");
  }
  void nonNegative(const std::string& key, double v, double max) const {
    if (!(std::isfinite(v) && v >= 0.0 && v <= max)) add(key, v, "must be in [0, " + show(max) + "]");
  }
  void fraction(const std::string& key, double v) const {
    if (!(std::isfinite(v) && v > 0.0 && v <= 1.0)) add(key, v, "must be in (0, 1]");
  }
  void integer(const std::string& key, int v, int min, int max) const {
    if (v < min || v > max) add(key, std::to_string(v), "must be an integer in " + std::to_string(min) + ".." + std::to_string(max));
  }
  bool failed() const { return fields_.failed(); }
  /// True if `key` or a section or list item it lies in is unread.
  bool isUnread(const std::string& key) const {
    for (std::size_t end = 0; end != std::string::npos;) {
      end = key.find_first_of(".[", end + 1);
      if (unread_.count(key.substr(0, end)) != 0) return true;
    }
    return false;
  }

 private:
  const YamlFields& fields_;
  std::map<std::string, YAML::Node> nodes_;
  std::set<std::string> unread_;
};

// ---- validation: ranges, then relations -------------------------------------------------

void checkBody(const Problems& p, const D& d) {
  if (d.body.shape == D::Shape::kCircle) {
    p.positive("body.diameter_m", d.body.diameter_m, 10.0);
  } else {
    p.positive("body.length_m", d.body.length_m, 10.0);
    p.positive("body.width_m", d.body.width_m, 10.0);
  }
  p.positive("body.mass_kg", d.body.mass_kg, 10000.0);
  p.positive("body.com_height_m", d.body.com_height_m, 5.0);
}

void checkChamberRanges(const Problems& p, const D& d) {
  const auto& c = d.chambers;
  switch (c.layout) {
    case D::Layout::kRing:
      p.integer("chambers.count", c.count, 3, c.centre_radius_m > 0.0 ? kMaxChambers - 1 : kMaxChambers);
      p.positive("chambers.sealed_diameter_m", c.sealed_diameter_m, 10.0);
      p.nonNegative("chambers.centre_radius_m", c.centre_radius_m, 5.0);
      if (c.centre_radius_m > 0.0) p.positive("chambers.centre_volume_m3", c.centre_volume_m3, 10.0);
      break;
    case D::Layout::kGrid:
      p.integer("chambers.rows", c.rows, 1, kMaxChambers);
      p.integer("chambers.columns", c.columns, 1, kMaxChambers);
      if (c.rows >= 1 && c.columns >= 1 && c.rows * c.columns > kMaxChambers) {
        p.add("chambers.columns", std::to_string(c.columns),
              "rows x columns = " + std::to_string(c.rows * c.columns) + " chambers, more than " +
                  std::to_string(kMaxChambers));
      }
      p.positive("chambers.length_m", c.length_m, 10.0);
      p.positive("chambers.width_m", c.width_m, 10.0);
      break;
    case D::Layout::kSingle:
      if (c.shape == D::Shape::kCircle) {
        p.positive("chambers.diameter_m", c.diameter_m, 10.0);
      } else {
        p.positive("chambers.length_m", c.length_m, 10.0);
        p.positive("chambers.width_m", c.width_m, 10.0);
      }
      break;
    case D::Layout::kPolygons:
      if (c.polygons.empty() || static_cast<int>(c.polygons.size()) > kMaxChambers) {
        p.add("chambers.polygons", std::to_string(c.polygons.size()) + " chambers",
              "must list 1.." + std::to_string(kMaxChambers) + " chambers");
      }
      for (std::size_t i = 0; i < c.polygons.size(); ++i) {
        p.positive(polygonKey(i, "volume_m3"), c.polygons[i].volume_m3, 10.0);
        if (c.polygons[i].outline.size() < 3) {
          p.add(polygonKey(i, "outline_m"), std::to_string(c.polygons[i].outline.size()) + " points",
                "needs at least 3 corners");
        }
      }
      break;
  }
  if (c.layout != D::Layout::kPolygons) p.positive("chambers.volume_m3", c.volume_m3, 10.0);
}

void checkWheelRanges(const Problems& p, const D& d) {
  if (d.wheels.empty() || static_cast<int>(d.wheels.size()) > kMaxWheels) {
    p.add("wheels", std::to_string(d.wheels.size()) + " wheels", "must list 1.." + std::to_string(kMaxWheels) + " wheels");
  }
  for (std::size_t i = 0; i < d.wheels.size(); ++i) {
    const auto& w = d.wheels[i];
    p.positive(wheelKey(i, "radius_m"), w.radius_m, 1.0);
    p.positive(wheelKey(i, "friction_coefficient"), w.friction_coefficient, 10.0);
    if (w.chamber != 0) {
      const bool ring = d.chambers.layout == D::Layout::kRing;
      if (ring && p.isUnread("chambers.count")) continue;
      if (!ring || w.chamber < 1 || w.chamber > d.chambers.count) {
        p.add(wheelKey(i, "chamber"), std::to_string(w.chamber),
              d.chambers.layout == D::Layout::kRing
                  ? "must be a ring chamber 1.." + std::to_string(d.chambers.count) + " (chambers.count)"
                  : std::string("a wheel is placed by chamber only in a ring layout: give x_m and y_m"));
      }
      p.positive(wheelKey(i, "mount_radius_m"), w.mount_radius_m, 5.0);
    } else {
      if (!std::isfinite(w.x_m)) p.add(wheelKey(i, "x_m"), w.x_m, "must be a finite number");
      if (!std::isfinite(w.y_m)) p.add(wheelKey(i, "y_m"), w.y_m, "must be a finite number");
    }
  }
}

void checkAirRanges(const Problems& p, const D& d) {
  if (d.reservoir.present) p.positive("reservoir.volume_m3", d.reservoir.volume_m3, 100.0);
  p.positive("sealing.strip_width_m", d.sealing.strip_width_m, 1.0);
  p.positive("sealing.travel_m", d.sealing.travel_m, 0.5);
  p.positive("sealing.max_slope", d.sealing.max_slope, 100.0);
  p.nonNegative("sealing.basic_gap_m", d.sealing.basic_gap_m, 0.1);
  p.nonNegative("sealing.kappa_L", d.sealing.kappa_L, 100.0);
  p.integer("engines.count", d.engines.count, 1, kMaxEngines);
  p.positive("engines.dp_max_pa", d.engines.dp_max_pa, 1e5);
  p.positive("engines.flow_max_m3ps", d.engines.flow_max_m3ps, 100.0);
  p.positive("engines.speed_lag_s", d.engines.speed_lag_s, 3600.0);
  if (d.reservoir.present) {
    p.positive("valves.max_area_m2", d.valves.max_area_m2, 1.0);
    p.fraction("valves.discharge_coefficient", d.valves.discharge_coefficient);
    p.positive("valves.full_stroke_s", d.valves.full_stroke_s, 3600.0);
    p.nonNegative("valves.command_delay_s", d.valves.command_delay_s, 3600.0);
  }
  p.positive("drive.max_speed_mps", d.drive.max_speed_mps, 100.0);
  p.positive("drive.max_steering_rate_degps", d.drive.max_steering_rate_radps / kDegToRad, 36000.0);
  p.positive("adhesion.desired_downforce_n", d.adhesion.desired_downforce_n, 1e6);
  p.positive("gas.ambient_pressure_pa", d.gas.ambient_pressure_pa, 1e7);
  p.positive("gas.temperature_k", d.gas.temperature_k, 1000.0);
  if (!(d.gas.kappa > 1.0 && d.gas.kappa <= 5.0 / 3.0)) {
    p.add("gas.kappa", d.gas.kappa, "must be in (1, 5/3] (adiabatic exponent)");  // 5/3: monatomic
  }
  p.positive("gas.r_air_jpkgk", d.gas.r_air_jpkgk, 1e5);
  p.positive("gas.rho_kgpm3", d.gas.rho_kgpm3, 1000.0);
}

/// The chamber count of a layout whose numbers passed their ranges.
int chamberCount(const D& d) { return d.chambers.total(); }

void checkEngineConnections(const Problems& p, const D& d) {
  const auto& chambers = d.engines.chambers;
  if (d.reservoir.present) {
    if (!chambers.empty()) {
      p.add("engines.chambers", show(chambers), "only without a reservoir: with one, the engines pump the reservoir");
    }
    return;
  }
  if (static_cast<int>(chambers.size()) != d.engines.count) {
    p.add("engines.chambers", show(chambers),
          "without a reservoir, name the chamber of each of the " + std::to_string(d.engines.count) +
              " engines (engines.count)");
  }
  for (const int c : chambers) {
    if (c < 1 || c > chamberCount(d)) {
      p.add("engines.chambers", show(chambers),
            "chamber " + std::to_string(c) + " is not a chamber 1.." + std::to_string(chamberCount(d)));
    }
  }
}

bool insideBody(const D& d, RobotGeometry::Point q, double margin_m) {
  if (d.body.shape == D::Shape::kCircle) return std::hypot(q.x_m, q.y_m) + margin_m <= d.body.diameter_m / 2.0 + 1e-12;
  return std::abs(q.x_m) + margin_m <= d.body.length_m / 2.0 + 1e-12 &&
         std::abs(q.y_m) + margin_m <= d.body.width_m / 2.0 + 1e-12;
}

std::string bodyText(const D& d) {
  return d.body.shape == D::Shape::kCircle ? "body.diameter_m = " + show(d.body.diameter_m)
                                           : "body " + show(d.body.length_m) + " m x " + show(d.body.width_m) + " m";
}

/// The key that sets a chamber's outline, for messages.
std::string outlineKey(const D& d, std::size_t chamber) {
  switch (d.chambers.layout) {
    case D::Layout::kRing: return "chambers.sealed_diameter_m";
    case D::Layout::kGrid: return "chambers.length_m";
    case D::Layout::kSingle: return d.chambers.shape == D::Shape::kCircle ? "chambers.diameter_m" : "chambers.length_m";
    case D::Layout::kPolygons: return polygonKey(chamber, "outline_m");
  }
  return "chambers";
}

void checkRingRelations(const Problems& p, const D& d) {
  const double w = d.sealing.strip_width_m;
  const double r1 = d.chambers.centre_radius_m;
  const double r2 = d.chambers.sealed_diameter_m / 2.0;
  if (r1 == 0.0) return;
  if (r1 <= w / 2.0) {
    p.add("chambers.centre_radius_m", r1,
          "must be > " + show(w / 2.0) + " (sealing.strip_width_m / 2) or the inner strip covers the centre chamber");
  }
  if (r1 >= r2 - w) {
    p.add("chambers.centre_radius_m", r1,
          "must be < " + show(r2 - w) +
              " (chambers.sealed_diameter_m / 2 - sealing.strip_width_m) or the inner and outer strips overlap");
  }
  const double corner_gap_m = 2.0 * r1 * std::sin(kPi / d.chambers.count);
  if (corner_gap_m <= w) {
    p.add("chambers.count", std::to_string(d.chambers.count),
          "too many chambers: neighbouring radial strips are " + show(corner_gap_m) +
              " m apart at chambers.centre_radius_m, less than sealing.strip_width_m");
  }
}

/// Chambers inside the body, simple, not overlapping, one closed outer strip; wheels inside
/// the body and clear of every strip; downforce reachable.
void checkGeometry(const Problems& p, const D& d) {
  if (d.chambers.layout == D::Layout::kRing) checkRingRelations(p, d);
  if (p.failed()) return;
  const auto outlines = chamberOutlines(d);
  const double half_strip = d.sealing.strip_width_m / 2.0;
  bool sound = true;
  for (std::size_t i = 0; i < outlines.size(); ++i) {
    const bool own = d.chambers.layout == D::Layout::kPolygons;
    if (own && (robot::selfIntersects(outlines[i]) || std::abs(robot::signedArea(outlines[i])) <= 0.0)) {
      p.add(outlineKey(d, i), std::to_string(outlines[i].size()) + " corners",
            "chamber " + std::to_string(i + 1) + "'s outline crosses itself or encloses no area");
      sound = false;
      continue;
    }
    for (const auto& q : outlines[i]) {
      if (!insideBody(d, q, half_strip)) {
        p.add(outlineKey(d, i), "(" + show(q.x_m) + ", " + show(q.y_m) + ")",
              "chamber " + std::to_string(i + 1) + " with its strip (sealing.strip_width_m / 2) reaches outside the body (" +
                  bodyText(d) + ") at (" + show(q.x_m) + ", " + show(q.y_m) + ")");
        sound = false;
        break;
      }
    }
    if (!sound && !own) return;  // a generated layout: its first chamber says it all
  }
  if (!sound) return;
  if (d.chambers.layout == D::Layout::kPolygons) {
    for (std::size_t i = 0; i < outlines.size(); ++i) {
      for (std::size_t j = i + 1; j < outlines.size(); ++j) {
        if (robot::overlap(outlines[i], outlines[j])) {
          p.add(polygonKey(j, "outline_m"), "chamber " + std::to_string(j + 1),
                "overlaps chamber " + std::to_string(i + 1));
          sound = false;
        }
      }
    }
    if (!sound) return;
    for (const auto& problem : robot::sealingSegments(outlines).problems) p.add("chambers.polygons", "", problem);
  }
  if (p.failed()) return;
  const RobotGeometry g = computeGeometry(d);
  if (static_cast<int>(g.segments.size()) > kMaxSegments) {
    p.add("chambers", std::to_string(g.segments.size()) + " sealing segments",
          "more than " + std::to_string(kMaxSegments) + " sealing segments: fewer chambers or simpler outlines");
  }
  for (std::size_t i = 0; i < d.wheels.size(); ++i) {
    const auto& at = g.wheels[i].p_RobotWheel;
    const std::string key = wheelKey(i, d.wheels[i].chamber != 0 ? "mount_radius_m" : "x_m");
    const std::string value = "(" + show(at.x_m) + ", " + show(at.y_m) + ")";
    if (!insideBody(d, at, 0.0)) {
      p.add(key, value, "the wheel's contact point lies outside the body (" + bodyText(d) + ")");
      continue;
    }
    // A caster's contact trails its swivel axis by its radius, all round.
    const bool caster = d.wheels[i].kind == D::WheelKind::kCaster;
    const double clearance_m = half_strip + (caster ? d.wheels[i].radius_m : 0.0);
    for (const auto& s : g.segments) {
      const double gap_m = robot::distanceToPolyline(s.centreline_Robot, at);
      if (gap_m < clearance_m) {
        p.add(key, value,
              std::string(caster ? "the caster's swivel circle" : "the wheel's contact point") +
                  " lies on the sealing strip " + s.name + " (" + show(gap_m) + " m from its centre line, less than " +
                  (caster ? "sealing.strip_width_m / 2 + its radius_m)" : "sealing.strip_width_m / 2)"));
        break;
      }
    }
  }
  const double max_downforce_n = d.engines.dp_max_pa * g.suctionArea();
  if (d.adhesion.desired_downforce_n > max_downforce_n) {
    p.add("adhesion.desired_downforce_n", d.adhesion.desired_downforce_n,
          "must be <= " + show(max_downforce_n) + " (engines.dp_max_pa * sealed area): the engines cannot reach more");
  }
  const double rho_ideal = d.gas.ambient_pressure_pa / (d.gas.r_air_jpkgk * d.gas.temperature_k);
  if (std::abs(d.gas.rho_kgpm3 - rho_ideal) > kRhoTolerance * rho_ideal) {
    p.add("gas.rho_kgpm3", d.gas.rho_kgpm3,
          "must be within 10 % of " + show(rho_ideal) + " (gas.ambient_pressure_pa / (gas.r_air_jpkgk * gas.temperature_k))");
  }
}

void validateWith(const Problems& p, const D& d) {
  if (d.name.empty()) p.add("name", "''", "must be a non-empty string");
  checkBody(p, d);
  checkChamberRanges(p, d);
  checkWheelRanges(p, d);
  checkAirRanges(p, d);
  if (p.failed()) return;  // the relations need valid numbers
  checkEngineConnections(p, d);
  checkGeometry(p, d);
}

// ---- reading the YAML file -----------------------------------------------------------------

/// Reads one mapping's keys, recording missing required ones and each key's node.
class Section {
 public:
  Section(const YamlFields& f, Problems& p, const YAML::Node& node, const std::string& path)
      : f_(f), p_(p), map_(f, node, path), path_(path) {}

  void number(const char* key, double& value, double yaml_to_si = 1.0) {
    if (!present(key)) return;
    double v = value;
    if (map_.number(key, v)) {
      value = v * yaml_to_si;
    } else {
      p_.unread(map_.full(key));
    }
  }
  void integer(const char* key, int& value) {
    if (present(key) && !map_.integer(key, value, 0, 1000)) p_.unread(map_.full(key));
  }
  void optionalNumber(const char* key, double& value) {
    remember(key);
    map_.number(key, value);
  }
  void optionalBoolean(const char* key, bool& value) {
    remember(key);
    map_.boolean(key, value);
  }
  /// One of `names` (its index), or nullopt if absent or not one of them (recorded).
  std::optional<int> choice(const char* key, const std::vector<const char*>& names, bool required) {
    if (required ? !present(key) : !remember(key)) return std::nullopt;
    const YAML::Node node = map_.take(key);
    std::optional<int> found;
    f_.check([&] {
      const std::string text = f_.text(node, map_.full(key));
      for (std::size_t i = 0; i < names.size(); ++i) {
        if (text == names[i]) found = static_cast<int>(i);
      }
      if (!found) {
        p_.unread(map_.full(key));
        std::string list;
        for (const char* n : names) list += (list.empty() ? "" : ", ") + std::string(n);
        f_.fail(node, map_.full(key), "must be one of " + list);
      }
    });
    return found;
  }
  YAML::Node take(const char* key) {
    remember(key);
    return map_.take(key);
  }
  /// Notes `key` as missing if absent (reported by done()); true if present.
  bool present(const char* key) {
    if (remember(key)) return true;
    missing_.push_back(key);
    p_.unread(map_.full(key));
    return false;
  }
  /// Records the unknown keys, else the missing ones: a missing key of a map with an unknown
  /// one is most likely the one misspelt, and the unknown key says it all.
  void done() const {
    bool unknown = false;
    for (const auto& item : map_.node()) {
      const std::string key = item.first.as<std::string>();
      if (std::find(known_.begin(), known_.end(), key) == known_.end()) unknown = true;
    }
    if (!unknown) {
      for (const auto& key : missing_) f_.check([&] { f_.required(map_.node(), path_, key); });
    }
    map_.rejectUnknown();
  }
  YamlMap& map() { return map_; }

 private:
  bool remember(const char* key) {
    known_.emplace_back(key);
    map_.take(key);  // known to rejectUnknown's list even when absent
    const YAML::Node node = map_.node()[key];
    if (!node.IsDefined()) return false;
    p_.node(map_.full(key), node);
    return true;
  }

  const YamlFields& f_;
  Problems& p_;
  YamlMap map_;
  std::string path_;
  std::vector<std::string> known_;
  std::vector<std::string> missing_;
};

/// Runs `body(section)` on the mapping `root[key]`, recording a missing or malformed section.
template <class Body>
void section(const YamlFields& f, Problems& p, const YAML::Node& root, const char* key, Body&& body) {
  const YAML::Node node = root[key];
  if (!node.IsDefined()) {
    p.unread(key);
    f.check([&] { f.required(root, "", key); });
    return;
  }
  const bool read = f.check([&] {
    Section s(f, p, node, key);
    body(s);
    s.done();
  });
  if (!read) p.unread(key);
}

D::Shape shapeOf(int index) { return index == 0 ? D::Shape::kCircle : D::Shape::kRectangle; }

RobotDescription::Point point(const YamlFields& f, const YAML::Node& node, const std::string& key) {
  if (!node.IsSequence() || node.size() != 2) f.fail(node, key, "must be a point [x_m, y_m]");
  return {f.number(node[0], key), f.number(node[1], key)};
}

void readChambers(const YamlFields& f, Problems& p, Section& s, D& d) {
  auto& c = d.chambers;
  const auto layout = s.choice("layout", {"ring", "grid", "single", "polygons"}, true);
  if (!layout) return;
  c.layout = static_cast<D::Layout>(*layout);
  switch (c.layout) {
    case D::Layout::kRing:
      s.integer("count", c.count);
      s.number("sealed_diameter_m", c.sealed_diameter_m);
      s.optionalNumber("centre_radius_m", c.centre_radius_m);
      if (c.centre_radius_m > 0.0) s.number("centre_volume_m3", c.centre_volume_m3);
      s.number("volume_m3", c.volume_m3);
      break;
    case D::Layout::kGrid:
      s.integer("rows", c.rows);
      s.integer("columns", c.columns);
      s.number("length_m", c.length_m);
      s.number("width_m", c.width_m);
      s.number("volume_m3", c.volume_m3);
      break;
    case D::Layout::kSingle: {
      const auto shape = s.choice("shape", {"circle", "rectangle"}, true);
      if (!shape) return;
      c.shape = shapeOf(*shape);
      if (c.shape == D::Shape::kCircle) {
        s.number("diameter_m", c.diameter_m);
      } else {
        s.number("length_m", c.length_m);
        s.number("width_m", c.width_m);
      }
      s.number("volume_m3", c.volume_m3);
      break;
    }
    case D::Layout::kPolygons: {
      if (!s.present("polygons")) return;
      const YAML::Node list = s.take("polygons");
      if (!list.IsSequence()) f.fail(list, "chambers.polygons", "must be a list of {outline_m, volume_m3}");
      for (std::size_t i = 0; i < list.size(); ++i) {
        D::PolygonChamber chamber;
        const std::string path = "chambers.polygons[" + std::to_string(i + 1) + "]";
        f.check([&] {
          Section item(f, p, list[i], path);
          if (item.present("outline_m")) {
            const YAML::Node outline = item.take("outline_m");
            if (!outline.IsSequence()) f.fail(outline, path + ".outline_m", "must be a list of points [x_m, y_m]");
            for (const auto& corner : outline) chamber.outline.push_back(point(f, corner, path + ".outline_m"));
          }
          item.number("volume_m3", chamber.volume_m3);
          item.done();
        });
        c.polygons.push_back(std::move(chamber));
      }
      break;
    }
  }
}

void readWheels(const YamlFields& f, Problems& p, const YAML::Node& root, D& d) {
  const YAML::Node list = root["wheels"];
  if (!list.IsDefined()) {
    p.unread("wheels");
    f.check([&] { f.required(root, "", "wheels"); });
    return;
  }
  p.node("wheels", list);
  if (!list.IsSequence()) {
    p.unread("wheels");
    f.check([&] { f.fail(list, "wheels", "must be a list of wheels ({kind, chamber and mount_radius_m or x_m and y_m, radius_m, friction_coefficient})"); });
    return;
  }
  for (std::size_t i = 0; i < list.size(); ++i) {
    D::Wheel w;
    f.check([&] {
      Section s(f, p, list[i], "wheels[" + std::to_string(i + 1) + "]");
      const auto kind = s.choice("kind", {"steerable", "fixed", "caster"}, true);
      if (kind) w.kind = static_cast<D::WheelKind>(*kind);
      if (s.map().node()["chamber"].IsDefined()) {
        s.integer("chamber", w.chamber);
        s.number("mount_radius_m", w.mount_radius_m);
      } else {
        s.number("x_m", w.x_m);
        s.number("y_m", w.y_m);
      }
      s.number("radius_m", w.radius_m);
      s.number("friction_coefficient", w.friction_coefficient);
      s.done();
    });
    d.wheels.push_back(w);
  }
}

D parse(const YamlFields& f, Problems& p, const YAML::Node& root) {
  D d;
  YamlMap top(f, root, "");
  for (const char* key : {"name", "body", "chambers", "reservoir", "sealing", "engines", "valves", "wheels", "drive",
                          "adhesion", "gas"}) {
    top.take(key);
  }
  top.rejectUnknown();
  if (!root["name"].IsDefined()) {
    f.check([&] { f.required(root, "", "name"); });
  } else {
    p.node("name", root["name"]);
    f.check([&] { d.name = f.text(root["name"], "name"); });
  }
  section(f, p, root, "body", [&](Section& s) {
    const auto shape = s.choice("shape", {"circle", "rectangle"}, false);
    if (shape) d.body.shape = shapeOf(*shape);
    if (d.body.shape == D::Shape::kCircle) {
      s.number("diameter_m", d.body.diameter_m);
    } else {
      s.number("length_m", d.body.length_m);
      s.number("width_m", d.body.width_m);
    }
    s.number("mass_kg", d.body.mass_kg);
    s.number("com_height_m", d.body.com_height_m);
  });
  section(f, p, root, "chambers", [&](Section& s) { readChambers(f, p, s, d); });
  d.reservoir.present = root["reservoir"].IsDefined();
  if (d.reservoir.present) {
    section(f, p, root, "reservoir", [&](Section& s) { s.number("volume_m3", d.reservoir.volume_m3); });
  }
  section(f, p, root, "sealing", [&](Section& s) {
    s.number("strip_width_m", d.sealing.strip_width_m);
    s.number("travel_m", d.sealing.travel_m);
    s.number("max_slope", d.sealing.max_slope);
    s.number("basic_gap_m", d.sealing.basic_gap_m);
    s.number("kappa_L", d.sealing.kappa_L);
    s.optionalBoolean("channel_bound", d.sealing.channel_bound);
  });
  section(f, p, root, "engines", [&](Section& s) {
    s.integer("count", d.engines.count);
    s.number("dp_max_pa", d.engines.dp_max_pa);
    s.number("flow_max_m3ps", d.engines.flow_max_m3ps);
    s.number("speed_lag_s", d.engines.speed_lag_s);
    const YAML::Node chambers = s.take("chambers");
    if (chambers.IsDefined()) {
      if (!chambers.IsSequence()) f.fail(chambers, "engines.chambers", "must be a list of chamber numbers");
      for (const auto& c : chambers) d.engines.chambers.push_back(static_cast<int>(f.integer(c, "engines.chambers", -1000000, 1000000)));
    } else if (!d.reservoir.present) {
      f.check([&] { f.required(s.map().node(), "engines", "chambers"); });
    }
  });
  if (d.reservoir.present) {
    section(f, p, root, "valves", [&](Section& s) {
      s.number("max_area_m2", d.valves.max_area_m2);
      s.number("discharge_coefficient", d.valves.discharge_coefficient);
      s.number("full_stroke_s", d.valves.full_stroke_s);
      s.number("command_delay_s", d.valves.command_delay_s);
    });
  } else if (root["valves"].IsDefined()) {
    f.check([&] {
      f.failKey(root["valves"], "valves", "a robot without a reservoir has no valves (the engines pump the chambers directly)");
    });
  }
  readWheels(f, p, root, d);
  section(f, p, root, "drive", [&](Section& s) {
    s.number("max_speed_mps", d.drive.max_speed_mps);
    s.number("max_steering_rate_degps", d.drive.max_steering_rate_radps, kDegToRad);
  });
  section(f, p, root, "adhesion", [&](Section& s) { s.number("desired_downforce_n", d.adhesion.desired_downforce_n); });
  section(f, p, root, "gas", [&](Section& s) {
    s.number("ambient_pressure_pa", d.gas.ambient_pressure_pa);
    s.number("temperature_k", d.gas.temperature_k);
    s.number("kappa", d.gas.kappa);
    s.number("r_air_jpkgk", d.gas.r_air_jpkgk);
    s.number("rho_kgpm3", d.gas.rho_kgpm3);
  });
  return d;
}

}  // namespace

double RobotDescription::Body::outerRadius() const {
  return shape == Shape::kCircle ? diameter_m / 2.0 : std::hypot(length_m, width_m) / 2.0;
}

int RobotDescription::Chambers::total() const {
  switch (layout) {
    case Layout::kRing: return count + (centre_radius_m > 0.0 ? 1 : 0);
    case Layout::kGrid: return rows * columns;
    case Layout::kSingle: return 1;
    case Layout::kPolygons: return static_cast<int>(polygons.size());
  }
  return 0;
}

const char* toString(RobotDescription::Shape shape) {
  return shape == RobotDescription::Shape::kCircle ? "circle" : "rectangle";
}

const char* toString(RobotDescription::Layout layout) {
  switch (layout) {
    case RobotDescription::Layout::kRing: return "ring";
    case RobotDescription::Layout::kGrid: return "grid";
    case RobotDescription::Layout::kSingle: return "single";
    case RobotDescription::Layout::kPolygons: return "polygons";
  }
  return "?";
}

const char* toString(RobotDescription::WheelKind kind) {
  switch (kind) {
    case RobotDescription::WheelKind::kSteerable: return "steerable";
    case RobotDescription::WheelKind::kFixed: return "fixed";
    case RobotDescription::WheelKind::kCaster: return "caster";
  }
  return "?";
}

RobotDescription loadRobotDescription(const std::string& path) {
  const YamlFields fields(path);
  const YAML::Node root = YamlFields::loadFile(path, "robot description");
  Problems problems(fields);
  RobotDescription d;
  if (fields.check([&] { d = parse(fields, problems, root); })) validateWith(problems, d);
  fields.finish();
  return d;
}

void validateRobotDescription(const RobotDescription& description, const std::string& source) {
  const YamlFields fields(source);
  Problems problems(fields);
  validateWith(problems, description);
  fields.finish();
}

}  // namespace climbsim
