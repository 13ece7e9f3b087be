#include "climbsim/wall/scene_xml.hpp"

#include <tinyxml2.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <functional>
#include <initializer_list>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "climbsim/errors.hpp"
#include "climbsim/wall/pose_offset.hpp"

namespace climbsim::scene {
namespace {

namespace fs = std::filesystem;

constexpr double kRadPerDeg = M_PI / 180.0;
constexpr int kRootNode = 0;
constexpr int kUnresolved = -2;

/// attribute="value", the value cut to about 60 characters for messages.
std::string quoted(const std::string& attribute, const std::string& value) {
  constexpr std::size_t kMaxShown = 60;
  const std::string shown = value.size() > kMaxShown ? value.substr(0, kMaxShown - 3) + "..." : value;
  return attribute.substr(0, kMaxShown) + "=\"" + shown + "\"";
}

/// Physical ranges of the scene's numbers: beyond them a value is a typo.
constexpr double kMaxSceneExtent_m = 1e5;   ///< offsets, sizes
constexpr double kMaxSensorRange_m = 1000.0;
constexpr double kMaxCameraLimit_m = 100.0;  ///< |near_limit|, |far_limit|
constexpr double kMaxAngle_deg = 3600.0;     ///< |roll|, |pitch|, |yaw| of an offset
constexpr int kMaxImageSide_px = 16384;

/// One tag of a scene file with its location, for attribute access and messages.
class Tag {
 public:
  Tag(const tinyxml2::XMLElement& element, const std::string& file)
      : element_(element), where_(file + ":" + std::to_string(element.GetLineNum())) {
    const char* name = element.Attribute("name");
    const std::string shown = name ? std::string(name).substr(0, 60) : std::string();
    label_ = std::string(element.Name()) + (name ? " \"" + shown + "\"" : "");
  }

  const std::string& where() const { return where_; }

  [[noreturn]] void fail(const std::string& problem) const { throw ConfigError(where_ + ": " + label_ + ": " + problem); }
  [[noreturn]] void failAttribute(const std::string& attribute, const std::string& problem) const {
    fail(quoted(attribute, value(attribute).value_or("")) + ": " + problem);
  }

  void allowOnly(std::initializer_list<const char*> allowed) const {
    for (const tinyxml2::XMLAttribute* a = element_.FirstAttribute(); a != nullptr; a = a->Next()) {
      const bool known = std::any_of(allowed.begin(), allowed.end(),
                                     [&](const char* name) { return std::string(name) == a->Name(); });
      if (!known) {
        std::string list;
        for (const char* name : allowed) list += std::string(list.empty() ? "" : ", ") + name;
        fail("unknown attribute " + quoted(a->Name(), a->Value()) + " (allowed: " + list + ")");
      }
    }
  }

  std::optional<std::string> value(const std::string& attribute) const {
    const char* v = element_.Attribute(attribute.c_str());
    return v ? std::optional<std::string>(v) : std::nullopt;
  }

  std::string required(const std::string& attribute) const {
    auto v = value(attribute);
    if (!v) fail("attribute " + attribute + " is missing");
    return *v;
  }

  /// A required non-empty name.
  std::string name() const {
    const std::string n = required("name");
    if (n.empty()) failAttribute("name", "empty name");
    return n;
  }

  double number(const std::string& attribute) const {
    double v = 0.0;
    if (!parseNumber(required(attribute), v)) failAttribute(attribute, "not a finite number");
    return v;
  }

  double positive(const std::string& attribute, double max = kMaxSceneExtent_m) const {
    const double v = number(attribute);
    if (!(v > 0.0)) failAttribute(attribute, "must be > 0");
    if (v > max) failAttribute(attribute, "must be at most " + shortNumber(max));
    return v;
  }

  double within(const std::string& attribute, double max_abs) const {
    const double v = number(attribute);
    if (std::abs(v) > max_abs) failAttribute(attribute, "must be within +-" + shortNumber(max_abs));
    return v;
  }

  Pose offset() const {
    const auto text = value("offset");
    Pose pose = Pose::Identity();
    std::string problem;
    if (text && !parseOffset(*text, pose, problem)) failAttribute("offset", problem);
    if (text) {
      std::istringstream in(*text);
      double v = 0.0;
      for (int i = 0; i < 6 && in >> v; ++i) {
        if (i < 3 && std::abs(v) > kMaxSceneExtent_m) failAttribute("offset", "x y z must be within +-1e5 m");
        if (i >= 3 && std::abs(v) > kMaxAngle_deg) failAttribute("offset", "roll pitch yaw must be within +-3600 degrees");
      }
    }
    return pose;
  }

  static std::string shortNumber(double v) {
    std::ostringstream out;
    out << v;
    return out.str();
  }

 private:
  const tinyxml2::XMLElement& element_;
  std::string where_;
  std::string label_;
};

/// Where something is attached, before the tree exists.
struct AttachRef {
  std::string attached_to;
  int scope = -1;  ///< raw part that includes the declaring file; -1: the top file
  std::string where;
  std::string label;  ///< `part "X"` etc., for messages
};

struct RawPart {
  std::string name;
  Pose offset = Pose::Identity();
  int mesh = -1;
  AttachRef ref;
  int parent_node = kUnresolved;  ///< node index once resolved (0 ROOT, k raw part k-1)
};

class Loader {
 public:
  SceneDescription load(const std::string& path) {
    out_.file = path;
    if (!fs::is_regular_file(path)) {
      throw ConfigError(path + ": no such scene file");
    }
    readFile(path, -1, {});
    resolveParts();
    buildTree();
    resolveOthers();
    return std::move(out_);
  }

 private:
  static int scopeRootNode(int scope) { return scope < 0 ? kRootNode : scope + 1; }

  void readFile(const std::string& path, int scope, std::vector<std::string> stack) {
    stack.push_back(fs::weakly_canonical(path).string());
    tinyxml2::XMLDocument doc;
    if (doc.LoadFile(path.c_str()) != tinyxml2::XML_SUCCESS) {
      std::string reason = doc.ErrorStr() ? doc.ErrorStr() : "cannot read";
      throw ConfigError(path + ":" + std::to_string(doc.ErrorLineNum()) + ": not well-formed XML (" + reason + ")");
    }
    const tinyxml2::XMLElement* root = doc.RootElement();
    if (root == nullptr || std::string(root->Name()) != "scene") {
      throw ConfigError(path + ":" + std::to_string(root ? root->GetLineNum() : 1) + ": root tag <" +
                        (root ? root->Name() : "") + ">, expected <scene>");
    }
    Tag(*root, path).allowOnly({});
    for (const auto* e = root->FirstChildElement(); e != nullptr; e = e->NextSiblingElement()) {
      const Tag tag(*e, path);
      const std::string kind = e->Name();
      if (kind == "part") {
        readPart(tag, path, scope, stack);
      } else if (kind == "element") {
        readElement(tag, scope);
      } else if (kind == "distance_sensor") {
        readDistanceSensor(tag, scope);
      } else if (kind == "camera") {
        readCamera(tag, scope);
      } else {
        throw ConfigError(tag.where() + ": unknown tag <" + kind +
                          "> (expected part, element, distance_sensor or camera)");
      }
    }
  }

  AttachRef attachRef(const Tag& tag, int scope, const std::string& label) {
    return AttachRef{tag.required("attached_to"), scope, tag.where(), label};
  }

  void readPart(const Tag& tag, const std::string& path, int scope, const std::vector<std::string>& stack) {
    tag.allowOnly({"name", "file", "attached_to", "offset"});
    RawPart part;
    part.name = tag.name();
    if (part.name.find(':') != std::string::npos) tag.failAttribute("name", "a part name may not contain ':'");
    if (part.name == "ROOT") tag.failAttribute("name", "ROOT is the root's name");
    part.ref = attachRef(tag, scope, "part \"" + part.name + "\"");
    part.offset = tag.offset();
    const std::string file = tag.value("file").value_or("");
    const int index = static_cast<int>(raw_.size());
    raw_.push_back(part);
    if (file.empty()) return;

    fs::path resolved = fs::path(file);
    if (resolved.is_relative()) resolved = fs::path(path).parent_path() / resolved;
    resolved = resolved.lexically_normal();
    if (!fs::is_regular_file(resolved)) {
      tag.failAttribute("file", "no such file (" + resolved.string() + ")");
    }
    std::string extension = resolved.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (extension == ".xml") {
      const std::string canonical = fs::weakly_canonical(resolved).string();
      if (std::find(stack.begin(), stack.end(), canonical) != stack.end()) {
        std::string chain;
        for (const auto& f : stack) chain += f + " -> ";
        tag.failAttribute("file", "cycle of insertion points: " + chain + canonical);
      }
      readFile(resolved.string(), index, stack);
      return;
    }
    const std::string canonical = fs::weakly_canonical(resolved).string();
    auto cached = mesh_index_.find(canonical);
    if (cached == mesh_index_.end()) {
      out_.meshes.push_back(loadMeshFile(resolved.string(), tag.where() + ": part \"" + part.name + "\"", quoted("file", file)));
      cached = mesh_index_.emplace(canonical, static_cast<int>(out_.meshes.size()) - 1).first;
    }
    raw_[index].mesh = cached->second;
  }

  void readElement(const Tag& tag, int scope) {
    const std::string name = tag.name();
    const std::string type = tag.required("type");
    if (!element_names_.insert(name).second) tag.failAttribute("name", "a second element of this name");
    if (type == "3d Pose") {
      tag.allowOnly({"name", "type", "attached_to", "angle_type"});
      PoseElement element;
      element.name = name;
      element.where = tag.where();
      const std::string angle_type = tag.required("angle_type");
      if (angle_type != "rad" && angle_type != "deg") tag.failAttribute("angle_type", "expected \"rad\" or \"deg\"");
      element.angles_in_degrees = angle_type == "deg";
      out_.pose_elements.push_back(element);
      pose_refs_.push_back(attachRef(tag, scope, "element \"" + name + "\""));
    } else if (type == "Switch") {
      tag.allowOnly({"name", "type", "attached_to", "switch_mode"});
      SwitchElement element;
      element.name = name;
      element.where = tag.where();
      const std::string mode = tag.required("switch_mode");
      if (mode != "-3" && mode != "-1") tag.failAttribute("switch_mode", "expected -3 (on) or -1 (off)");
      element.on = mode == "-3";
      out_.switches.push_back(element);
      switch_refs_.push_back(attachRef(tag, scope, "element \"" + name + "\""));
    } else {
      tag.failAttribute("type", "unknown element type (expected \"3d Pose\" or \"Switch\")");
    }
  }

  void readDistanceSensor(const Tag& tag, int scope) {
    tag.allowOnly({"name", "attached_to", "max_distance", "scan_angle_range", "angular_resolution", "offset"});
    DistanceSensorInfo sensor;
    sensor.name = tag.name();
    if (!sensor_names_.insert("distance_sensor " + sensor.name).second) {
      tag.failAttribute("name", "a second distance_sensor of this name");
    }
    sensor.where = tag.where();
    sensor.T_part_sensor = tag.offset();
    sensor.max_distance_m = tag.positive("max_distance", kMaxSensorRange_m);
    const double range_deg = tag.positive("scan_angle_range");
    if (range_deg > 360.0) tag.failAttribute("scan_angle_range", "must be at most 360 degrees");
    const double resolution_deg = tag.positive("angular_resolution");
    if (resolution_deg > range_deg) tag.failAttribute("angular_resolution", "larger than scan_angle_range");
    sensor.scan_angle_range_rad = range_deg * kRadPerDeg;
    sensor.angular_resolution_rad = resolution_deg * kRadPerDeg;
    out_.distance_sensors.push_back(sensor);
    sensor_refs_.push_back(attachRef(tag, scope, "distance_sensor \"" + sensor.name + "\""));
  }

  void readCamera(const Tag& tag, int scope) {
    tag.allowOnly({"name", "attached_to", "type", "near_limit", "far_limit", "width", "height", "size", "offset"});
    CameraInfo camera;
    camera.name = tag.name();
    if (!sensor_names_.insert("camera " + camera.name).second) tag.failAttribute("name", "a second camera of this name");
    camera.where = tag.where();
    camera.type = tag.required("type");
    if (camera.type != "orthographic") tag.failAttribute("type", "only \"orthographic\" cameras are supported");
    camera.T_part_camera = tag.offset();
    camera.near_limit_m = tag.within("near_limit", kMaxCameraLimit_m);
    if (tag.value("far_limit")) {
      camera.far_limit_m = tag.within("far_limit", kMaxCameraLimit_m);
      if (!(camera.far_limit_m > camera.near_limit_m)) tag.failAttribute("far_limit", "must be > near_limit");
    }
    for (const char* attribute : {"width", "height"}) {
      if (!tag.value(attribute)) continue;
      const std::string text = *tag.value(attribute);
      double v = 0.0;
      if (!parseNumber(text, v) || v != std::floor(v) || v < 1.0 || v > kMaxImageSide_px) {
        tag.failAttribute(attribute, "expected a whole number of pixels in 1..16384");
      }
      (std::string(attribute) == "width" ? camera.width_px : camera.height_px) = static_cast<int>(v);
    }
    if (const auto size = tag.value("size")) {
      std::istringstream in(*size);
      std::vector<double> values;
      std::string token;
      while (in >> token) {
        double v = 0.0;
        if (!parseNumber(token, v) || !(v > 0.0) || v > kMaxSceneExtent_m) {
          tag.failAttribute("size", "'" + token.substr(0, 60) + "' is not a number in (0, 1e5] m");
        }
        values.push_back(v);
      }
      if (values.empty() || values.size() > 2) tag.failAttribute("size", "expected \"w h\" or \"w\" in metres");
      camera.width_m = values[0];
      camera.height_m = values.back();
    }
    out_.cameras.push_back(camera);
    camera_refs_.push_back(attachRef(tag, scope, "camera \"" + camera.name + "\""));
  }

  // ------------------------------------------------------------------ resolution

  bool declaredWithin(int raw_index, int scope) const {
    for (int s = raw_[raw_index].ref.scope; s >= 0; s = raw_[s].ref.scope) {
      if (s == scope) return true;
    }
    return scope < 0;
  }

  [[noreturn]] static void failRef(const AttachRef& ref, const std::string& problem) {
    throw ConfigError(ref.where + ": " + ref.label + ": " + quoted("attached_to", ref.attached_to) + ": " + problem);
  }

  /// Node the reference names, kUnresolved if the tree does not (yet) contain it.
  int resolve(const AttachRef& ref) const {
    const std::string& target = ref.attached_to;
    if (target.empty()) failRef(ref, "empty");
    if (target == "ROOT") return scopeRootNode(ref.scope);
    if (target.find(':') == std::string::npos) {
      std::vector<int> found;
      for (int i = 0; i < static_cast<int>(raw_.size()); ++i) {
        if (raw_[i].name == target && declaredWithin(i, ref.scope)) found.push_back(i);
      }
      if (found.size() > 1) {
        failRef(ref, "ambiguous, " + std::to_string(found.size()) + " parts of that name (declared at " +
                         raw_[found[0]].ref.where + " and " + raw_[found[1]].ref.where + "); give the full name");
      }
      if (found.empty()) failRef(ref, "names no insertion point");
      return found[0] + 1;
    }
    std::vector<std::string> steps;
    std::string step;
    std::istringstream in(target);
    while (std::getline(in, step, ':')) steps.push_back(step);
    if (steps.front() != "ROOT") failRef(ref, "a full name starts with ROOT");
    int node = scopeRootNode(ref.scope);
    for (std::size_t k = 1; k < steps.size(); ++k) {
      std::vector<int> children;
      for (int i = 0; i < static_cast<int>(raw_.size()); ++i) {
        if (raw_[i].parent_node == node && raw_[i].name == steps[k]) children.push_back(i + 1);
      }
      if (children.size() > 1) failRef(ref, "ambiguous: two parts named " + steps[k] + " at the same place");
      if (children.empty()) return kUnresolved;
      node = children[0];
    }
    return node;
  }

  void resolveParts() {
    // Short names resolve at once; full names wait until their path exists.
    bool progress = true;
    while (progress) {
      progress = false;
      for (auto& part : raw_) {
        if (part.parent_node != kUnresolved) continue;
        part.parent_node = resolve(part.ref);
        progress = progress || part.parent_node != kUnresolved;
      }
    }
    for (int i = 0; i < static_cast<int>(raw_.size()); ++i) {
      std::vector<int> chain = {i + 1};
      int node = raw_[i].parent_node;
      while (node > kRootNode && chain.size() <= raw_.size() + 1) {
        if (std::find(chain.begin(), chain.end(), node) != chain.end()) {
          std::string names;
          for (int n : chain) names += raw_[n - 1].name + " -> ";
          failRef(raw_[i].ref, "cycle of insertion points: " + names + raw_[node - 1].name);
        }
        chain.push_back(node);
        node = raw_[node - 1].parent_node;
      }
    }
    for (const auto& part : raw_) {
      if (part.parent_node == kUnresolved) failRef(part.ref, "names no insertion point");
    }
    // A full name resolved early could have become ambiguous by a part attached later.
    for (const auto& part : raw_) resolve(part.ref);
  }

  void buildTree() {
    std::vector<std::vector<int>> children(raw_.size() + 1);
    for (int i = 0; i < static_cast<int>(raw_.size()); ++i) children[raw_[i].parent_node].push_back(i + 1);
    node_to_part_.assign(raw_.size() + 1, -1);
    PartInfo root;
    root.name = root.full_name = "ROOT";
    out_.parts.push_back(root);
    node_to_part_[kRootNode] = 0;
    // Two parts at one place under one name could never be told apart
    // (docs/scene-files.md#scene-xml).
    std::map<std::string, std::string> declared_at;
    std::function<void(int)> visit = [&](int node) {
      for (int child : children[node]) {
        const RawPart& raw = raw_[child - 1];
        PartInfo part;
        part.name = raw.name;
        part.parent = node_to_part_[node];
        part.full_name = out_.parts[part.parent].full_name + ":" + raw.name;
        const auto [first, inserted] = declared_at.emplace(part.full_name, raw.ref.where);
        if (!inserted) {
          throw ConfigError(raw.ref.where + ": part \"" + raw.name + "\": the full name " + part.full_name +
                            " is already the part declared at " + first->second + "; give it another name");
        }
        part.T_parent_part = raw.offset;
        part.mesh = raw.mesh;
        part.where = raw.ref.where;
        node_to_part_[child] = static_cast<int>(out_.parts.size());
        out_.parts.push_back(part);
        visit(child);
      }
    };
    visit(kRootNode);
  }

  int partOf(const AttachRef& ref) const {
    const int node = resolve(ref);
    if (node == kUnresolved) failRef(ref, "names no insertion point");
    return node_to_part_[node];
  }

  void resolveOthers() {
    std::set<int> posed;
    for (std::size_t k = 0; k < out_.pose_elements.size(); ++k) {
      auto& element = out_.pose_elements[k];
      element.part = partOf(pose_refs_[k]);
      if (element.part == 0) failRef(pose_refs_[k], "a 3d Pose element cannot move ROOT");
      if (!posed.insert(element.part).second) failRef(pose_refs_[k], "the part already has a 3d Pose element");
    }
    for (std::size_t k = 0; k < out_.switches.size(); ++k) out_.switches[k].part = partOf(switch_refs_[k]);
    for (std::size_t k = 0; k < out_.distance_sensors.size(); ++k) {
      out_.distance_sensors[k].part = partOf(sensor_refs_[k]);
    }
    for (std::size_t k = 0; k < out_.cameras.size(); ++k) out_.cameras[k].part = partOf(camera_refs_[k]);
  }

  SceneDescription out_;
  std::vector<RawPart> raw_;
  std::vector<int> node_to_part_;
  std::map<std::string, int> mesh_index_;
  std::set<std::string> element_names_;
  std::set<std::string> sensor_names_;
  std::vector<AttachRef> pose_refs_, switch_refs_, sensor_refs_, camera_refs_;
};

}  // namespace

SceneDescription loadSceneDescription(const std::string& path) { return Loader().load(path); }

}  // namespace climbsim::scene
