#include "climbsim/robot/robot_description.hpp"

#include <yaml-cpp/yaml.h>

#include <charconv>
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

/// `text` on one line, cut to about 60 characters for messages.
std::string cut(const std::string& text) {
  constexpr std::size_t kMax = 60;
  std::string out;
  for (const char c : text) out += (c == '\n' || c == '\r' || c == '\t') ? ' ' : c;
  return out.size() > kMax ? out.substr(0, kMax - 3) + "..." : out;
}

/// Where a key's value came from, so that every error can point at the file line.
struct Origin {
  int line = 0;
  std::string text;
};

/// Throws the one-line ConfigError of a bad key; shows the YAML text when the key was read
/// from a file, else the value as the description holds it (in the key's units).
class Blame {
 public:
  Blame(std::string source, const std::map<std::string, Origin>* origins)
      : source_(std::move(source)), origins_(origins) {}

  [[noreturn]] void operator()(const std::string& key, const std::string& value, const std::string& why) const {
    const Origin* origin = find(key);
    throw ConfigErrorAt(where(origin) + ": " + key + " = " + cut(origin ? origin->text : value) + ": " + why,
                        origin ? origin->line : 0);
  }
  [[noreturn]] void operator()(const std::string& key, double value, const std::string& why) const {
    (*this)(key, show(value), why);
  }
  [[noreturn]] void key(const std::string& key, int line, const std::string& why) const {
    throw ConfigErrorAt((line > 0 ? source_ + ":" + std::to_string(line) : source_) + ": " + cut(key) + ": " + why, line);
  }

 private:
  const Origin* find(const std::string& key) const {
    if (!origins_) return nullptr;
    const auto it = origins_->find(key);
    return it == origins_->end() ? nullptr : &it->second;
  }
  std::string where(const Origin* origin) const {
    return origin && origin->line > 0 ? source_ + ":" + std::to_string(origin->line) : source_;
  }

  std::string source_;
  const std::map<std::string, Origin>* origins_;
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

/// `unread`: keys whose value did not read (already reported).
void validateWith(const Blame& blame, const RobotDescription& description, ErrorList& errors,
                  const std::set<std::string>& unread = {}) {
  RobotDescription d = description;  // the field tables hand out mutable references
  if (d.name.empty() && unread.count(kNameKey) == 0) {
    errors.check([&] { blame(kNameKey, "''", "must be a non-empty string"); });
  }
  for (const auto& f : numberFields()) {
    if (unread.count(f.key) == 0) errors.check([&] { checkRule(blame, f, f.member(d)); });
  }
  for (const auto& f : integerFields()) {
    const int v = f.member(d);
    if (unread.count(f.key) == 0 && (v < f.min || v > f.max)) {
      errors.check([&] {
        blame(f.key, std::to_string(v), "must be an integer in " + std::to_string(f.min) + ".." + std::to_string(f.max));
      });
    }
  }
  if (!errors.empty()) return;  // the relations need valid numbers
  if (unread.count(kWheelChambersKey) != 0) return;
  errors.check([&] { checkWheelChambers(blame, d); });
  errors.check([&] { checkGeometry(blame, d); });
}

// ---- reading the YAML file ----

int lineOf(const YAML::Node& node) {
  const YAML::Mark mark = node.Mark();
  return mark.is_null() ? 0 : mark.line + 1;
}

std::string textOf(const YAML::Node& node) {
  if (node.IsNull()) return "null";
  if (node.IsScalar()) return node.Scalar().empty() ? "''" : node.Scalar();
  YAML::Emitter emitter;
  emitter << YAML::Flow << node;
  return emitter.good() ? emitter.c_str() : "?";
}

std::string childrenOf(const std::string& prefix, const std::vector<std::string>& keys) {
  std::set<std::string> names;
  for (const auto& k : keys) {
    if (prefix.empty()) {
      names.insert(k.substr(0, k.find('.')));
    } else if (k.rfind(prefix + ".", 0) == 0) {
      const std::string rest = k.substr(prefix.size() + 1);
      names.insert(rest.substr(0, rest.find('.')));
    }
  }
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

/// Records where each known key is and rejects unknown and duplicate keys, before any value is
/// read, so that a typo is reported as such and not as the missing key it was meant to be.
/// `unknown_in`: the sections (prefixes, "" for the top level) with an unknown key: a key
/// missing there is most likely the one misspelt, reported as unknown already.
void scanKeys(const Blame& blame, const YAML::Node& map, const std::string& prefix,
              const std::vector<std::string>& keys, std::map<std::string, Origin>& origins, ErrorList& errors,
              std::set<std::string>& unknown_in) {
  const std::string what = prefix.empty() ? "the file" : prefix;
  if (!map.IsMap()) {
    blame.key((prefix.empty() ? "(top level)" : prefix) + " = " + textOf(map), lineOf(map),
              "must be a mapping of " + childrenOf(prefix, keys));
  }
  std::set<std::string> seen;
  for (const auto& item : map) {
    const std::string name = item.first.IsScalar() ? item.first.Scalar() : textOf(item.first);
    const std::string key = prefix.empty() ? name : prefix + "." + name;
    if (!seen.insert(name).second) {
      errors.check([&] { blame.key(key, lineOf(item.first), "duplicate key"); });
      continue;
    }
    bool leaf = false;
    bool section = false;
    for (const auto& k : keys) {
      leaf = leaf || k == key;
      section = section || k.rfind(key + ".", 0) == 0;
    }
    if (leaf) {
      origins[key] = Origin{lineOf(item.second), textOf(item.second)};
    } else if (section) {
      errors.check([&] { scanKeys(blame, item.second, key, keys, origins, errors, unknown_in); });
    } else {
      unknown_in.insert(prefix);
      errors.check([&] {
        blame.key(key, lineOf(item.first), "unknown key (known keys of " + what + ": " + childrenOf(prefix, keys) + ")");
      });
    }
  }
}

/// The node of a dotted key; a missing key or section is an error naming the first missing part.
YAML::Node lookup(const Blame& blame, const YAML::Node& root, const std::string& key) {
  YAML::Node node = root;
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = key.find('.', start);
    const std::string part = key.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    // Through a const node so that a missing key is not inserted; reset() rebinds where
    // operator= would overwrite the parent's value.
    const YAML::Node child = static_cast<const YAML::Node&>(node)[part];
    if (!child.IsDefined()) blame.key(key.substr(0, dot), lineOf(node), "missing");
    node.reset(child);
    if (dot == std::string::npos) return node;
    start = dot + 1;
  }
}

double readNumber(const Blame& blame, const YAML::Node& node, const std::string& key) {
  if (node.IsScalar()) {
    try {
      return node.as<double>();
    } catch (const YAML::Exception&) {
    }
  }
  blame(key, textOf(node), "must be a number");
}

int readInteger(const Blame& blame, const YAML::Node& node, const std::string& key) {
  int value = 0;
  if (node.IsScalar()) {
    const std::string& text = node.Scalar();
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error == std::errc() && end == text.data() + text.size() && !text.empty()) return value;
  }
  blame(key, textOf(node), "must be an integer");
}

RobotDescription parse(const Blame& blame, const YAML::Node& root, ErrorList& errors, std::set<std::string>& unread,
                       const std::map<std::string, Origin>& origins, const std::set<std::string>& unknown_in) {
  RobotDescription d;
  // A key missing from a section with an unknown key: the unknown key says it all.
  const auto explained = [&](const std::string& key) {
    const auto dot = key.rfind('.');
    return origins.count(key) == 0 && unknown_in.count(dot == std::string::npos ? "" : key.substr(0, dot)) != 0;
  };
  if (!errors.check([&] {
        const YAML::Node name = lookup(blame, root, kNameKey);
        if (!name.IsScalar() || name.Scalar().empty()) blame(kNameKey, textOf(name), "must be a non-empty string");
        d.name = name.Scalar();
      })) {
    unread.insert(kNameKey);
  }
  for (const auto& f : numberFields()) {
    if (explained(f.key) ||
        !errors.check([&] { f.member(d) = readNumber(blame, lookup(blame, root, f.key), f.key) * f.yaml_to_si; })) {
      unread.insert(f.key);
    }
  }
  for (const auto& f : integerFields()) {
    if (explained(f.key) || !errors.check([&] { f.member(d) = readInteger(blame, lookup(blame, root, f.key), f.key); })) {
      unread.insert(f.key);
    }
  }
  if (!errors.check([&] {
        const YAML::Node wheels = lookup(blame, root, kWheelChambersKey);
        if (!wheels.IsSequence()) blame(kWheelChambersKey, textOf(wheels), "must be a list of chamber numbers");
        for (const auto& item : wheels) d.wheels.chambers.push_back(readInteger(blame, item, kWheelChambersKey));
      })) {
    unread.insert(kWheelChambersKey);
  }
  return d;
}

}  // namespace

RobotDescription loadRobotDescription(const std::string& path) {
  const Blame plain(path, nullptr);
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw ConfigError(path + ": cannot read the robot description");
  } catch (const YAML::ParserException& e) {
    throw ConfigError(path + ":" + std::to_string(e.mark.line + 1) + ": not valid YAML: " + e.msg);
  } catch (const YAML::Exception& e) {
    throw ConfigError(path + ": not valid YAML: " + e.msg);
  }
  std::map<std::string, Origin> origins;
  ErrorList errors;
  std::set<std::string> unknown_in;
  errors.check([&] { scanKeys(plain, root, "", allKeys(), origins, errors, unknown_in); });
  const Blame blame(path, &origins);
  std::set<std::string> unread;
  RobotDescription d = parse(blame, root, errors, unread, origins, unknown_in);
  if (origins.count(kChannelBoundKey) != 0) {
    const YamlFields fields(path);
    const YAML::Node& file = root;  // const: lookups insert nothing
    errors.check([&] { d.sealing.channel_bound = fields.boolean(file["sealing"]["channel_bound"], kChannelBoundKey); });
  }
  validateWith(blame, d, errors, unread);
  errors.throwIfAny();
  return d;
}

void validateRobotDescription(const RobotDescription& description, const std::string& source) {
  ErrorList errors;
  validateWith(Blame(source, nullptr), description, errors);
  errors.throwIfAny();
}

}  // namespace climbsim
