#include "climbsim/wall_patches/patch_spec_yaml.hpp"

#include <cctype>

#include "climbsim/errors.hpp"
#include "climbsim/yaml_fields.hpp"

namespace climbsim::surface {
namespace {

std::string located(const std::string& source, const YAML::Node& node) {
  const int line = YamlFields::lineOf(node);
  return line > 0 ? source + ":" + std::to_string(line) : source;
}

/// The patch spec's own value kinds on top of common/'s YamlMap (which records every problem
/// of the file in its YamlFields, "<file>:<line>: <key> = <value>: <why>", as the scenario,
/// robot and compose files).
class SpecMap : public YamlMap {
 public:
  using YamlMap::YamlMap;

  void seed(const char* key, std::uint64_t& value) {
    const YAML::Node item = take(key);
    if (!item) return;
    fields().check([&] {
      const std::string text = item.IsScalar() ? item.Scalar() : "";
      bool digits = !text.empty() && text.size() <= 20;
      for (char c : text) digits = digits && std::isdigit(static_cast<unsigned char>(c));
      if (!digits) fields().fail(item, full(key), "it must be an unsigned integer");
      try {
        value = std::stoull(text);
      } catch (const std::exception&) {
        fields().fail(item, full(key), "it is out of range for a 64-bit seed");
      }
    });
  }

  void profile(const char* key, Profile& value) {
    const YAML::Node item = take(key);
    if (!item) return;
    fields().check([&] {
      const std::string text = item.IsScalar() ? item.Scalar() : "";
      if (text == "rect") value = Profile::kRect;
      else if (text == "v") value = Profile::kV;
      else if (text == "u") value = Profile::kU;
      else fields().fail(item, full(key), "it must be rect, v or u");
    });
  }
};

void readLinear(const YamlFields& fields, const YAML::Node& node, const std::string& path, LinearFeature& f) {
  SpecMap r(fields, node, path);
  r.number("x_m", f.x_m);
  r.number("y_m", f.y_m);
  r.number("angle_deg", f.angle_deg);
  r.number("width_m", f.width_m);
  r.number("depth_m", f.depth_m);
  r.number("length_m", f.length_m);
  r.profile("profile", f.profile);
  r.rejectUnknown();
}

/// Each item of the list `key` (if present) read by `read` from a copy of `defaults`; an item
/// that is not a mapping is recorded and skipped.
template <typename T, typename Read>
void readList(SpecMap& parent, const char* key, std::vector<T>& list, const T& defaults, Read read) {
  const YAML::Node node = parent.take(key);
  if (!node) return;
  const YamlFields& fields = parent.fields();
  if (!fields.check([&] {
        if (!node.IsSequence()) fields.fail(node, key, "it must be a list");
      })) {
    return;
  }
  std::size_t index = 0;
  for (const auto& item : node) {
    T value = defaults;
    if (fields.check([&] { read(fields, item, std::string(key) + "[" + std::to_string(index) + "]", value); })) {
      list.push_back(value);
    }
    ++index;
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
  const YamlFields fields(source);
  fields.check([&] {
    SpecMap r(fields, root, "");
    r.number("size_m", spec.size_m);
    r.number("grid_m", spec.grid_m);
    r.number("wall_run_m", spec.wall_run_m);
    r.seed("seed", spec.seed);
    if (const YAML::Node rough = r.take("rough")) {
      fields.check([&] {
        SpecMap rr(fields, rough, "rough");
        rr.number("rms_m", spec.rough.rms_m);
        rr.number("correlation_length_m", spec.rough.correlation_length_m);
        rr.rejectUnknown();
      });
    }
    readList(r, "cracks", spec.cracks, LinearFeature{}, readLinear);
    LinearFeature groove;
    groove.width_m = 0.02;
    readList(r, "grooves", spec.grooves, groove, readLinear);
    if (const YAML::Node net = r.take("crack_network")) {
      fields.check([&] {
        SpecMap rn(fields, net, "crack_network");
        rn.integer("count", spec.network.count);
        rn.integer("segments", spec.network.segments);
        rn.number("segment_length_m", spec.network.segment_length_m);
        rn.number("turn_deg", spec.network.turn_deg);
        rn.number("width_m", spec.network.width_m);
        rn.number("depth_m", spec.network.depth_m);
        rn.profile("profile", spec.network.profile);
        rn.rejectUnknown();
      });
    }
    readList(r, "holes", spec.holes, Hole{},
             [](const YamlFields& f, const YAML::Node& node, const std::string& path, Hole& h) {
               SpecMap rh(f, node, path);
               rh.number("x_m", h.x_m);
               rh.number("y_m", h.y_m);
               rh.number("diameter_m", h.diameter_m);
               rh.number("depth_m", h.depth_m);
               rh.rejectUnknown();
             });
    readList(r, "steps", spec.steps, Step{},
             [](const YamlFields& f, const YAML::Node& node, const std::string& path, Step& st) {
               SpecMap rs(f, node, path);
               rs.number("x_m", st.x_m);
               rs.number("y_m", st.y_m);
               rs.number("angle_deg", st.angle_deg);
               rs.number("height_m", st.height_m);
               rs.rejectUnknown();
             });
    r.rejectUnknown();
  });
  fields.finish();
}

void validatePatchSpecFrom(const PatchSpec& spec, const YAML::Node& root, const std::string& source) {
  validatePatchSpec(spec, [&](const std::string& key) {
    const YAML::Node node = root ? nodeAt(root, key) : YAML::Node();
    return node ? located(source, node) : source;
  });
}

PatchSpec loadPatchSpecYaml(const std::string& path) {
  const YAML::Node root = YamlFields::loadFile(path, "patch spec");
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
