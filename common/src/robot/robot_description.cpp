#include "climbsim/robot/robot_description.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

#include "climbsim/errors.hpp"
#include "climbsim/yaml_fields.hpp"

namespace climbsim {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegToRad = kPi / 180.0;
/// Relative tolerance of rho against the ideal gas law: wide enough for deliberate choices
/// (e.g. a density at chamber pressure), narrow enough to catch a misplaced decimal point.
constexpr double kRhoTolerance = 0.10;

enum class Rule { kPositive, kNonNegative, kFraction, kAdiabaticExponent };

/// A numeric key of the YAML file; the description holds value * yaml_to_si.
struct NumberField {
  const char* key;
  Rule rule;
  double yaml_to_si;
  double& (*member)(RobotDescription&);
};

struct IntegerField {
  const char* key;
  int min;
  int max;
  int& (*member)(RobotDescription&);
};

// Every key is named here once; parsing, the unknown/missing checks and the range checks all
// come from these tables.
const std::vector<NumberField>& numberFields() {
  using D = RobotDescription;
  static const std::vector<NumberField> fields = {
      {"body.diameter_m", Rule::kPositive, 1.0, [](D& d) -> double& { return d.body.diameter_m; }},
      {"body.sealed_diameter_m", Rule::kPositive, 1.0, [](D& d) -> double& { return d.body.sealed_diameter_m; }},
      {"body.mass_kg", Rule::kPositive, 1.0, [](D& d) -> double& { return d.body.mass_kg; }},
      {"body.com_height_m", Rule::kPositive, 1.0, [](D& d) -> double& { return d.body.com_height_m; }},
      {"chambers.centre_radius_m", Rule::kPositive, 1.0, [](D& d) -> double& { return d.chambers.centre_radius_m; }},
      {"chambers.outer_volume_m3", Rule::kPositive, 1.0, [](D& d) -> double& { return d.chambers.outer_volume_m3; }},
      {"chambers.centre_volume_m3", Rule::kPositive, 1.0,
       [](D& d) -> double& { return d.chambers.centre_volume_m3; }},
      {"reservoir.volume_m3", Rule::kPositive, 1.0, [](D& d) -> double& { return d.reservoir.volume_m3; }},
      {"sealing.strip_width_m", Rule::kPositive, 1.0, [](D& d) -> double& { return d.sealing.strip_width_m; }},
      {"sealing.travel_m", Rule::kPositive, 1.0, [](D& d) -> double& { return d.sealing.travel_m; }},
      {"sealing.max_slope", Rule::kPositive, 1.0, [](D& d) -> double& { return d.sealing.max_slope; }},
      {"sealing.basic_gap_m", Rule::kNonNegative, 1.0, [](D& d) -> double& { return d.sealing.basic_gap_m; }},
      {"sealing.kappa_L", Rule::kNonNegative, 1.0, [](D& d) -> double& { return d.sealing.kappa_L; }},
      {"engines.dp_max_pa", Rule::kPositive, 1.0, [](D& d) -> double& { return d.engines.dp_max_pa; }},
      {"engines.flow_max_m3ps", Rule::kPositive, 1.0, [](D& d) -> double& { return d.engines.flow_max_m3ps; }},
      {"engines.speed_lag_s", Rule::kPositive, 1.0, [](D& d) -> double& { return d.engines.speed_lag_s; }},
      {"valves.max_area_m2", Rule::kPositive, 1.0, [](D& d) -> double& { return d.valves.max_area_m2; }},
      {"valves.discharge_coefficient", Rule::kFraction, 1.0,
       [](D& d) -> double& { return d.valves.discharge_coefficient; }},
      {"valves.full_stroke_s", Rule::kPositive, 1.0, [](D& d) -> double& { return d.valves.full_stroke_s; }},
      {"valves.command_delay_s", Rule::kNonNegative, 1.0, [](D& d) -> double& { return d.valves.command_delay_s; }},
      {"wheels.mount_radius_m", Rule::kPositive, 1.0, [](D& d) -> double& { return d.wheels.mount_radius_m; }},
      {"wheels.radius_m", Rule::kPositive, 1.0, [](D& d) -> double& { return d.wheels.radius_m; }},
      {"wheels.friction_coefficient", Rule::kPositive, 1.0,
       [](D& d) -> double& { return d.wheels.friction_coefficient; }},
      {"drive.max_speed_mps", Rule::kPositive, 1.0, [](D& d) -> double& { return d.drive.max_speed_mps; }},
      {"drive.max_steering_rate_degps", Rule::kPositive, kDegToRad,
       [](D& d) -> double& { return d.drive.max_steering_rate_radps; }},
      {"adhesion.desired_downforce_n", Rule::kPositive, 1.0,
       [](D& d) -> double& { return d.adhesion.desired_downforce_n; }},
      {"gas.ambient_pressure_pa", Rule::kPositive, 1.0, [](D& d) -> double& { return d.gas.ambient_pressure_pa; }},
      {"gas.temperature_k", Rule::kPositive, 1.0, [](D& d) -> double& { return d.gas.temperature_k; }},
      {"gas.kappa", Rule::kAdiabaticExponent, 1.0, [](D& d) -> double& { return d.gas.kappa; }},
      {"gas.r_air_jpkgk", Rule::kPositive, 1.0, [](D& d) -> double& { return d.gas.r_air_jpkgk; }},
      {"gas.rho_kgpm3", Rule::kPositive, 1.0, [](D& d) -> double& { return d.gas.rho_kgpm3; }},
  };
  return fields;
}

/// The physical upper bound of each number in the file's units: beyond it a value is a typo
/// (and would overflow the models' arithmetic).
double maxOf(const std::string& key) {
  static const std::map<std::string, double> maxima = {
      {"body.diameter_m", 10.0},           {"body.sealed_diameter_m", 10.0},
      {"body.mass_kg", 10000.0},           {"body.com_height_m", 5.0},
      {"chambers.centre_radius_m", 5.0},   {"chambers.outer_volume_m3", 10.0},
      {"chambers.centre_volume_m3", 10.0}, {"reservoir.volume_m3", 100.0},
      {"sealing.strip_width_m", 1.0},      {"sealing.travel_m", 0.5},
      {"sealing.max_slope", 100.0},        {"sealing.basic_gap_m", 0.1},
      {"sealing.kappa_L", 100.0},          {"engines.dp_max_pa", 1e5},
      {"engines.flow_max_m3ps", 100.0},    {"engines.speed_lag_s", 3600.0},
      {"valves.max_area_m2", 1.0},         {"valves.discharge_coefficient", 1.0},
      {"valves.full_stroke_s", 3600.0},    {"valves.command_delay_s", 3600.0},
      {"wheels.mount_radius_m", 5.0},      {"wheels.radius_m", 1.0},
      {"wheels.friction_coefficient", 10.0}, {"drive.max_speed_mps", 100.0},
      {"drive.max_steering_rate_degps", 36000.0}, {"adhesion.desired_downforce_n", 1e6},
      {"gas.ambient_pressure_pa", 1e7},    {"gas.temperature_k", 1000.0},
      {"gas.kappa", 5.0 / 3.0},            {"gas.r_air_jpkgk", 1e5},
      {"gas.rho_kgpm3", 1000.0},
  };
  const auto it = maxima.find(key);
  return it == maxima.end() ? 1e300 : it->second;
}

const std::vector<IntegerField>& integerFields() {
  using D = RobotDescription;
  static const std::vector<IntegerField> fields = {
      {"chambers.outer_count", 3, 36, [](D& d) -> int& { return d.chambers.outer_count; }},
      {"engines.count", 1, 16, [](D& d) -> int& { return d.engines.count; }},
  };
  return fields;
}

constexpr const char* kNameKey = "name";
constexpr const char* kWheelChambersKey = "wheels.chambers";
/// Optional (default false), read with YamlFields: the only boolean of the file.
constexpr const char* kChannelBoundKey = "sealing.channel_bound";

std::vector<std::string> allKeys() {
  std::vector<std::string> keys{kNameKey};
  for (const auto& f : numberFields()) keys.emplace_back(f.key);
  for (const auto& f : integerFields()) keys.emplace_back(f.key);
  keys.emplace_back(kWheelChambersKey);
  keys.emplace_back(kChannelBoundKey);
  return keys;
}

std::string show(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

std::string show(const std::vector<int>& values) {
  std::string out = "[";
  for (std::size_t i = 0; i < values.size(); ++i) {
    out += (i == 0 ? "" : ", ") + std::to_string(values[i]);
  }
  return out + "]";
}

/// Throws the one-line ConfigError of a bad key through YamlFields: "<file>:<line>: <key> =
/// <YAML text>: <why>" when the key was read from a file (its node is in `nodes`), else
/// "<source>: <key> = <value as the description holds it>: <why>".
class Blame {
 public:
  Blame(const YamlFields& fields, const std::map<std::string, YAML::Node>* nodes) : fields_(fields), nodes_(nodes) {}

  [[noreturn]] void operator()(const std::string& key, const std::string& value, const std::string& why) const {
    if (nodes_ != nullptr) {
      const auto it = nodes_->find(key);
      if (it != nodes_->end()) fields_.fail(it->second, key, why);
    }
    fields_.failValue(0, key, value, why);
  }
  [[noreturn]] void operator()(const std::string& key, double value, const std::string& why) const {
    (*this)(key, show(value), why);
  }

 private:
  const YamlFields& fields_;
  const std::map<std::string, YAML::Node>* nodes_;
};

void checkRule(const Blame& blame, const NumberField& field, double value_si) {
  const double v = value_si / field.yaml_to_si;
  if (!std::isfinite(v)) blame(field.key, v, "must be a finite number");
  const double max = maxOf(field.key);
  switch (field.rule) {
    case Rule::kPositive:
      if (!(v > 0.0 && v <= max)) blame(field.key, v, "must be in (0, " + show(max) + "]");
      break;
    case Rule::kNonNegative:
      if (!(v >= 0.0 && v <= max)) blame(field.key, v, "must be in [0, " + show(max) + "]");
      break;
    case Rule::kFraction:
      if (!(v > 0.0 && v <= 1.0)) blame(field.key, v, "must be in (0, 1]");
      break;
    case Rule::kAdiabaticExponent:
      // 5/3 is the monatomic ideal gas; no gas has a larger exponent.
      if (!(v > 1.0 && v <= 5.0 / 3.0)) blame(field.key, v, "must be in (1, 5/3] (adiabatic exponent)");
      break;
  }
}

void checkWheelChambers(const Blame& blame, const RobotDescription& d) {
  const auto& c = d.wheels.chambers;
  if (c.empty()) blame(kWheelChambersKey, show(c), "must list at least one chamber");
  std::set<int> seen;
  for (const int number : c) {
    if (number < 1 || number > d.chambers.outer_count) {
      blame(kWheelChambersKey, show(c),
            "chamber " + std::to_string(number) + " is not a ring chamber 1.." +
                std::to_string(d.chambers.outer_count) + " (chambers.outer_count)");
    }
    if (!seen.insert(number).second) {
      blame(kWheelChambersKey, show(c), "chamber " + std::to_string(number) + " is listed twice");
    }
  }
}

/// The relations between values; each violation blames the value most likely to be wrong.
void checkGeometry(const Blame& blame, const RobotDescription& d) {
  const double w = d.sealing.strip_width_m;
  const double r_body = d.body.diameter_m / 2.0;
  const double r1 = d.chambers.centre_radius_m;
  const double r2 = d.body.sealed_diameter_m / 2.0;
  const double sector_rad = 2.0 * kPi / d.chambers.outer_count;

  if (r2 + w / 2.0 > r_body) {
    blame("body.sealed_diameter_m", d.body.sealed_diameter_m,
          "must be <= " + show(2.0 * r_body - w) +
              " (body.diameter_m - sealing.strip_width_m) so that the outer strip fits on the body");
  }
  if (r1 <= w / 2.0) {
    blame("chambers.centre_radius_m", r1,
          "must be > " + show(w / 2.0) + " (sealing.strip_width_m / 2) or the inner strip covers the centre chamber");
  }
  if (r1 >= r2 - w) {
    blame("chambers.centre_radius_m", r1,
          "must be < " + show(r2 - w) +
              " (body.sealed_diameter_m / 2 - sealing.strip_width_m) or the inner and outer strips overlap");
  }
  const double corner_gap_m = 2.0 * r1 * std::sin(sector_rad / 2.0);
  if (corner_gap_m <= w) {
    blame("chambers.outer_count", std::to_string(d.chambers.outer_count),
          "too many chambers: neighbouring radial strips are " + show(corner_gap_m) +
              " m apart at chambers.centre_radius_m, less than sealing.strip_width_m");
  }
  const double mount_min = r1 + w / 2.0;
  const double mount_max = r2 - w / 2.0;
  if (!(d.wheels.mount_radius_m > mount_min && d.wheels.mount_radius_m < mount_max)) {
    blame("wheels.mount_radius_m", d.wheels.mount_radius_m,
          "must be in (" + show(mount_min) + ", " + show(mount_max) +
              "): inside the ring chambers, clear of the inner and outer strips");
  }
  const double max_downforce_n = d.engines.dp_max_pa * kPi * r2 * r2;
  if (d.adhesion.desired_downforce_n > max_downforce_n) {
    blame("adhesion.desired_downforce_n", d.adhesion.desired_downforce_n,
          "must be <= " + show(max_downforce_n) +
              " (engines.dp_max_pa * sealed area): the engines cannot reach more");
  }
  const double rho_ideal = d.gas.ambient_pressure_pa / (d.gas.r_air_jpkgk * d.gas.temperature_k);
  if (std::abs(d.gas.rho_kgpm3 - rho_ideal) > kRhoTolerance * rho_ideal) {
    blame("gas.rho_kgpm3", d.gas.rho_kgpm3,
          "must be within 10 % of " + show(rho_ideal) +
              " (gas.ambient_pressure_pa / (gas.r_air_jpkgk * gas.temperature_k))");
  }
}

/// Records every range and relation problem of `description` in `fields`. `unread`: keys
/// whose value did not read (already reported).
void validateWith(const YamlFields& fields, const Blame& blame, const RobotDescription& description,
                  const std::set<std::string>& unread = {}) {
  RobotDescription d = description;  // the field tables hand out mutable references
  if (d.name.empty() && unread.count(kNameKey) == 0) {
    fields.check([&] { blame(kNameKey, "''", "must be a non-empty string"); });
  }
  for (const auto& f : numberFields()) {
    if (unread.count(f.key) == 0) fields.check([&] { checkRule(blame, f, f.member(d)); });
  }
  for (const auto& f : integerFields()) {
    const int v = f.member(d);
    if (unread.count(f.key) == 0 && (v < f.min || v > f.max)) {
      fields.check([&] {
        blame(f.key, std::to_string(v), "must be an integer in " + std::to_string(f.min) + ".." + std::to_string(f.max));
      });
    }
  }
  if (fields.failed()) return;  // the relations need valid numbers
  if (unread.count(kWheelChambersKey) != 0) return;
  fields.check([&] { checkWheelChambers(blame, d); });
  fields.check([&] { checkGeometry(blame, d); });
}

// ---- reading the YAML file: the structure comes from the tables, the reading from YamlFields ----

/// The file's layout from the tables: the top-level keys in order, and each section's keys.
struct Layout {
  std::vector<std::string> top;
  std::vector<std::pair<std::string, std::vector<std::string>>> sections;
};

const Layout& layout() {
  static const Layout l = [] {
    Layout out;
    for (const std::string& key : allKeys()) {
      const auto dot = key.find('.');
      const std::string head = key.substr(0, dot);
      if (std::find(out.top.begin(), out.top.end(), head) == out.top.end()) out.top.push_back(head);
      if (dot == std::string::npos) continue;
      auto it = std::find_if(out.sections.begin(), out.sections.end(), [&](const auto& s) { return s.first == head; });
      if (it == out.sections.end()) it = out.sections.insert(out.sections.end(), {head, {}});
      it->second.push_back(key.substr(dot + 1));
    }
    return out;
  }();
  return l;
}

/// Checks the structure (every map a map, no unknown or duplicate key, no missing one) and
/// finds the node of every key it can; keys without a node are added to `unread`. A key
/// missing from a section with an unknown key is not reported: the unknown key is most likely
/// the one misspelt, and says it all.
void findNodes(const YamlFields& f, const YAML::Node& root, std::map<std::string, YAML::Node>& nodes,
               std::set<std::string>& unread) {
  const Layout& l = layout();
  const bool top_known = f.requireMap(root, "(document)", l.top);
  const auto leaf = [&](const YAML::Node& map, bool map_known, const std::string& section, const std::string& name) {
    const std::string key = section.empty() ? name : section + "." + name;
    const YAML::Node node = map[name];
    if (node.IsDefined()) {
      nodes[key].reset(node);
    } else {
      unread.insert(key);
      if (map_known && key != kChannelBoundKey) f.check([&] { f.required(map, section, name); });
    }
  };
  for (const auto& name : l.top) {
    if (std::none_of(l.sections.begin(), l.sections.end(), [&](const auto& s) { return s.first == name; })) {
      leaf(root, top_known, "", name);
    }
  }
  for (const auto& [section, keys] : l.sections) {
    const YAML::Node map = root[section];
    bool known = false;
    const bool usable = map.IsDefined() ? f.check([&] { known = f.requireMap(map, section, keys); })
                                        : (f.check([&] { f.required(root, "", section); }), false);
    for (const auto& name : keys) {
      if (usable) {
        leaf(map, known, section, name);
      } else {
        unread.insert(section + "." + name);
      }
    }
  }
}

RobotDescription parse(const YamlFields& f, const YAML::Node& root, std::map<std::string, YAML::Node>& nodes,
                       std::set<std::string>& unread) {
  findNodes(f, root, nodes, unread);
  RobotDescription d;
  const auto read = [&](const std::string& key, const auto& body) {
    if (unread.count(key) != 0) return;
    if (!f.check([&] { body(nodes.at(key)); })) unread.insert(key);
  };
  read(kNameKey, [&](const YAML::Node& node) { d.name = f.text(node, kNameKey); });
  for (const auto& field : numberFields()) {
    read(field.key, [&](const YAML::Node& node) { field.member(d) = f.number(node, field.key) * field.yaml_to_si; });
  }
  for (const auto& field : integerFields()) {
    read(field.key, [&](const YAML::Node& node) {
      field.member(d) = static_cast<int>(f.integer(node, field.key, field.min, field.max));
    });
  }
  read(kChannelBoundKey, [&](const YAML::Node& node) { d.sealing.channel_bound = f.boolean(node, kChannelBoundKey); });
  read(kWheelChambersKey, [&](const YAML::Node& node) {
    if (!node.IsSequence()) f.fail(node, kWheelChambersKey, "must be a list of chamber numbers");
    for (const auto& item : node) {
      d.wheels.chambers.push_back(static_cast<int>(f.integer(item, kWheelChambersKey, -1'000'000, 1'000'000)));
    }
  });
  return d;
}

}  // namespace

RobotDescription loadRobotDescription(const std::string& path) {
  const YamlFields fields(path);
  const YAML::Node root = YamlFields::loadFile(path, "robot description");
  std::map<std::string, YAML::Node> nodes;
  std::set<std::string> unread;
  RobotDescription d;
  if (fields.check([&] { d = parse(fields, root, nodes, unread); })) {
    validateWith(fields, Blame(fields, &nodes), d, unread);
  }
  fields.finish();
  return d;
}

void validateRobotDescription(const RobotDescription& description, const std::string& source) {
  const YamlFields fields(source);
  validateWith(fields, Blame(fields, nullptr), description);
  fields.finish();
}

}  // namespace climbsim
