#include "patch_spec_yaml.hpp"

#include <cctype>
#include <set>

#include "climbsim/errors.hpp"
#include "climbsim/yaml_fields.hpp"

namespace climbsim::surface {
namespace {

std::string located(const std::string& source, const YAML::Node& node) {
  const int line = YamlFields::lineOf(node);
  return line > 0 ? source + ":" + std::to_string(line) : source;
}

/// Reads one YAML map with known keys; each reader consumes its key. Parsing and the one-line
/// messages ("<file>:<line>: <key> = <value>: <why>") are common/'s YamlFields, as for the
/// scenario, robot and compose files.
class MapReader {
 public:
  MapReader(const YAML::Node& node, std::string path, const std::string& source)
      : node_(node), path_(std::move(path)), fields_(source) {
    if (!node_.IsMap()) fields_.fail(node_, path_.empty() ? "(document)" : path_, "it must be a mapping (key: value, ...)");
  }

  void number(const char* key, double& value) {
    const YAML::Node item = take(key);
    if (item) value = fields_.number(item, full(key));
  }

  void integer(const char* key, int& value) {
    const YAML::Node item = take(key);
    if (item) value = static_cast<int>(fields_.integer(item, full(key), -1'000'000'000, 1'000'000'000));
  }

  void seed(const char* key, std::uint64_t& value) {
    const YAML::Node item = take(key);
    if (!item) return;
    const std::string text = item.IsScalar() ? item.Scalar() : "";
    bool digits = !text.empty() && text.size() <= 20;
    for (char c : text) digits = digits && std::isdigit(static_cast<unsigned char>(c));
    if (!digits) fields_.fail(item, full(key), "it must be an unsigned integer");
    try {
      value = std::stoull(text);
    } catch (const std::exception&) {
      fields_.fail(item, full(key), "it is out of range for a 64-bit seed");
    }
  }

  void profile(const char* key, Profile& value) {
    const YAML::Node item = take(key);
    if (!item) return;
    const std::string text = item.IsScalar() ? item.Scalar() : "";
    if (text == "rect") value = Profile::kRect;
    else if (text == "v") value = Profile::kV;
    else if (text == "u") value = Profile::kU;
    else fields_.fail(item, full(key), "it must be rect, v or u");
  }

  YAML::Node take(const char* key) {
    known_.insert(key);
    const YAML::Node& map = node_;  // the const operator[] never inserts the key
    return map[key];
  }

  std::string full(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

  /// Call after all readers: a key nobody asked for is an error.
  void rejectUnknown() const {
    for (const auto& entry : node_) {
      const std::string key = entry.first.as<std::string>();
      if (!known_.count(key)) fields_.failKey(entry.first, full(key), "unknown key");
    }
  }

  const YamlFields& fields() const { return fields_; }

 private:
  YAML::Node node_;
  std::string path_;
  YamlFields fields_;
  std::set<std::string> known_;
};

void readLinear(const YAML::Node& node, const std::string& path, const std::string& source, LinearFeature& f) {
  MapReader r(node, path, source);
  r.number("x_m", f.x_m);
  r.number("y_m", f.y_m);
  r.number("angle_deg", f.angle_deg);
  r.number("width_m", f.width_m);
  r.number("depth_m", f.depth_m);
  r.number("length_m", f.length_m);
  r.profile("profile", f.profile);
  r.rejectUnknown();
}

template <typename T, typename Read>
void readList(MapReader& parent, const char* key, const std::string& source, std::vector<T>& list,
              const T& defaults, Read read) {
  const YAML::Node node = parent.take(key);
  if (!node) return;
  if (!node.IsSequence()) parent.fields().fail(node, key, "it must be a list");
  for (const auto& item : node) {
    T value = defaults;
    read(item, std::string(key) + "[" + std::to_string(list.size()) + "]", source, value);
    list.push_back(value);
  }
}

/// Finds the node of a key path like "cracks[2].width_m" (for line numbers).
/// Node::reset, not operator=, which would overwrite the node it refers to.
YAML::Node nodeAt(const YAML::Node& root, const std::string& key) {
  YAML::Node node;
  node.reset(root);
  std::size_t pos = 0;
  while (pos < key.size()) {
    std::size_t end = key.find_first_of(".[", pos);
    const std::string name = key.substr(pos, end == std::string::npos ? std::string::npos : end - pos);
    if (!node.IsMap()) return YAML::Node();
    const YAML::Node& map = node;
    const YAML::Node child = map[name];
    if (!child) return YAML::Node();
    node.reset(child);
    if (end == std::string::npos) break;
    if (key[end] == '[') {
      const std::size_t close = key.find(']', end);
      const std::size_t index = std::stoul(key.substr(end + 1, close - end - 1));
      if (!node.IsSequence() || index >= node.size()) return YAML::Node();
      const YAML::Node& list = node;
      const YAML::Node item = list[index];
      node.reset(item);
      end = close + 1;
    }
    pos = end + 1;
  }
  return node;
}

}  // namespace

void mergePatchSpec(PatchSpec& spec, const YAML::Node& root, const std::string& source) {
  if (!root || root.IsNull()) return;
  MapReader r(root, "", source);
  r.number("size_m", spec.size_m);
  r.number("grid_m", spec.grid_m);
  r.number("wall_run_m", spec.wall_run_m);
  r.seed("seed", spec.seed);
  if (const YAML::Node rough = r.take("rough")) {
    MapReader rr(rough, "rough", source);
    rr.number("rms_m", spec.rough.rms_m);
    rr.number("correlation_length_m", spec.rough.correlation_length_m);
    rr.rejectUnknown();
  }
  readList(r, "cracks", source, spec.cracks, LinearFeature{}, readLinear);
  LinearFeature groove;
  groove.width_m = 0.02;
  readList(r, "grooves", source, spec.grooves, groove, readLinear);
  if (const YAML::Node net = r.take("crack_network")) {
    MapReader rn(net, "crack_network", source);
    rn.integer("count", spec.network.count);
    rn.integer("segments", spec.network.segments);
    rn.number("segment_length_m", spec.network.segment_length_m);
    rn.number("turn_deg", spec.network.turn_deg);
    rn.number("width_m", spec.network.width_m);
    rn.number("depth_m", spec.network.depth_m);
    rn.profile("profile", spec.network.profile);
    rn.rejectUnknown();
  }
  readList(r, "holes", source, spec.holes, Hole{},
           [](const YAML::Node& node, const std::string& path, const std::string& src, Hole& h) {
             MapReader rh(node, path, src);
             rh.number("x_m", h.x_m);
             rh.number("y_m", h.y_m);
             rh.number("diameter_m", h.diameter_m);
             rh.number("depth_m", h.depth_m);
             rh.rejectUnknown();
           });
  readList(r, "steps", source, spec.steps, Step{},
           [](const YAML::Node& node, const std::string& path, const std::string& src, Step& s) {
             MapReader rs(node, path, src);
             rs.number("x_m", s.x_m);
             rs.number("y_m", s.y_m);
             rs.number("angle_deg", s.angle_deg);
             rs.number("height_m", s.height_m);
             rs.rejectUnknown();
           });
  r.rejectUnknown();
}

void validatePatchSpecFrom(const PatchSpec& spec, const YAML::Node& root, const std::string& source) {
  validatePatchSpec(spec, [&](const std::string& key) {
    const YAML::Node node = root ? nodeAt(root, key) : YAML::Node();
    return node ? located(source, node) : source;
  });
}

PatchSpec loadPatchSpecYaml(const std::string& path) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw ConfigError(path + ": cannot read the patch spec");
  } catch (const YAML::ParserException& e) {
    throw ConfigError(path + ":" + std::to_string(e.mark.line + 1) + ": YAML syntax: " + e.msg);
  }
  PatchSpec spec;
  mergePatchSpec(spec, root, path);
  validatePatchSpecFrom(spec, root, path);
  return spec;
}

YAML::Node keyValueList(const std::string& text, const std::string& option) {
  YAML::Node map(YAML::NodeType::Map);
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const std::size_t end = std::min(text.find(',', pos), text.size());
    const std::string item = text.substr(pos, end - pos);
    const std::size_t eq = item.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == item.size())
      throw ConfigError(option + ": '" + item + "': expected key=value (in '" + text + "')");
    map[item.substr(0, eq)] = item.substr(eq + 1);
    pos = end + 1;
  }
  return map;
}

}  // namespace climbsim::surface
