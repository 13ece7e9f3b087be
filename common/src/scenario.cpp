#include "climbsim/scenario.hpp"

#include "climbsim/robot_names.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "climbsim/errors.hpp"
#include "climbsim/yaml_fields.hpp"

namespace climbsim {
namespace {

constexpr const char* kBuildPrefix = "$BUILD/";
/// Highest downforce set-point a scenario may ask for [N].
constexpr double kMaxDownforceSetPoint_n = 1e6;
/// Latest time of a drive command, fault or picture [s] (a day: the longest scenario).
constexpr double kMaxTime_s = 86400.0;

/// A number in (0, max].
double positiveAtMost(const YamlFields& f, const YAML::Node& node, const std::string& key, double max) {
  const double value = f.positive(node, key);
  if (value > max) {
    std::ostringstream text;
    text << "it must be a number in (0, " << max << "]";
    f.fail(node, key, text.str());
  }
  return value;
}

/// Periods are whole steps: rate_hz must divide the lockstep rate (within 1e-9 relative).
std::int64_t periodSteps(const YamlFields& f, const YAML::Node& node, const std::string& key, double rate_hz,
                         std::int64_t step_ns) {
  const double steps = 1e9 / (rate_hz * static_cast<double>(step_ns));
  const double rounded = std::round(steps);
  if (rounded < 1.0 || std::abs(steps - rounded) > 1e-9 * steps) {
    f.fail(node, key,
           "it must divide the lockstep rate " + std::to_string(1e9 / static_cast<double>(step_ns)) +
               " Hz (1000 / step_ms) into whole steps");
  }
  return static_cast<std::int64_t>(rounded);
}

/// Longest `--set key=value` [characters]: a scenario value never needs more, and a longer one
/// is a mistake (a file's contents pasted as a value) that would otherwise be carried into every
/// service's scenario copy and log line. Longer values belong into the scenario file.
constexpr std::size_t kMaxOverrideChars = 4096;

void applyOverride(YAML::Node& root, const std::string& assignment) {
  if (assignment.size() > kMaxOverrideChars) {
    const auto eq = assignment.find('=');
    const std::string key = YamlFields::shortText(assignment.substr(0, std::min(eq, assignment.size())));
    throw ConfigError("--set " + key + "=...: " + std::to_string(assignment.size()) + " characters, at most " +
                      std::to_string(kMaxOverrideChars) + " (write long values into the scenario file)");
  }
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw ConfigError("--set " + YamlFields::shortText(assignment) + ": expected key=value, e.g. --set duration_s=5");
  }
  const std::string full_key = assignment.substr(0, eq);
  const std::string key = YamlFields::shortText(full_key);
  YAML::Node value;
  try {
    value = YAML::Load(assignment.substr(eq + 1));
  } catch (const YAML::Exception& e) {
    throw ConfigError("--set " + key + ": the value '" + YamlFields::shortText(assignment.substr(eq + 1)) +
                      "' is not YAML: " + e.msg);
  }
  std::vector<std::string> parts;
  std::stringstream in(full_key);
  for (std::string part; std::getline(in, part, '.');) {
    if (part.empty()) throw ConfigError("--set " + key + ": empty component in the key");
    parts.push_back(part);
  }
  YAML::Node node = root;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    const std::string& part = parts[i];
    if (node.IsSequence()) {
      const bool digits = std::all_of(part.begin(), part.end(), [](char c) { return c >= '0' && c <= '9'; });
      if (!digits || std::stoul(part) >= node.size()) {
        throw ConfigError("--set " + key + ": '" + part + "' is not an index of the list (0.." +
                          std::to_string(node.size() - 1) + ")");
      }
      node.reset(node[std::stoul(part)]);
    } else if (node.IsMap() || node.IsNull()) {
      YAML::Node child = node[part];
      if (!child.IsDefined() || child.IsNull()) {
        node[part] = YAML::Node(YAML::NodeType::Map);
        child = node[part];
      }
      node.reset(child);
    } else {
      throw ConfigError("--set " + key + ": '" + parts[i - 1] + "' is a value, not a mapping");
    }
  }
  node[parts.back()] = value;
}

Scenario::ControllerKind controllerKind(const YamlFields& f, const YAML::Node& node) {
  const std::string text = f.text(node, "controller.type");
  if (text == "none") return Scenario::ControllerKind::kNone;
  if (text == "fixed") return Scenario::ControllerKind::kFixed;
  if (text == "reference") return Scenario::ControllerKind::kReference;
  if (text == "external") return Scenario::ControllerKind::kExternal;
  if (text == "recorded") return Scenario::ControllerKind::kRecorded;
  f.fail(node, "controller.type", "it must be none, fixed, reference, external or recorded");
}

Scenario::Wall parseWall(const YamlFields& f, const YAML::Node& node) {
  f.requireMap(node, "wall", {"orientation", "overhang_deg", "wheels_on"});
  Scenario::Wall wall;
  if (node["orientation"]) {
    const std::string text = f.text(node["orientation"], "wall.orientation");
    if (text == "vertical") {
      wall.kind = Scenario::WallKind::kVertical;
    } else if (text == "floor") {
      wall.kind = Scenario::WallKind::kFloor;
    } else if (text == "overhang") {
      wall.kind = Scenario::WallKind::kOverhang;
    } else {
      f.fail(node["orientation"], "wall.orientation", "it must be vertical, floor or overhang");
    }
  }
  if (wall.kind == Scenario::WallKind::kOverhang) {
    if (!node["overhang_deg"]) f.failKey(node, "wall.overhang_deg", "missing; an overhang needs its angle past vertical");
    wall.overhang_deg = f.positive(node["overhang_deg"], "wall.overhang_deg");
    if (wall.overhang_deg > 90.0) f.fail(node["overhang_deg"], "wall.overhang_deg", "it must be in (0, 90]");
  } else if (node["overhang_deg"]) {
    f.fail(node["overhang_deg"], "wall.overhang_deg", "only an overhang wall has an overhang angle");
  }
  if (node["wheels_on"]) {
    const std::string text = f.text(node["wheels_on"], "wall.wheels_on");
    if (text == "plane") {
      wall.wheels_on = Scenario::WheelsOn::kPlane;
    } else if (text == "surface") {
      wall.wheels_on = Scenario::WheelsOn::kSurface;
    } else {
      f.fail(node["wheels_on"], "wall.wheels_on", "it must be plane or surface");
    }
  }
  return wall;
}

std::string resolveAgainst(const std::string& base_file, const std::string& path) {
  const std::filesystem::path p(path);
  if (p.is_absolute()) return p.lexically_normal().string();
  return (std::filesystem::path(base_file).parent_path() / p).lexically_normal().string();
}

Scenario::Controller parseController(const YamlFields& f, const YAML::Node& node, const std::string& source) {
  f.requireMap(node, "controller", {"type", "downforce_n", "balance", "valves", "commands"});
  if (!node["type"]) f.failKey(node, "controller.type", "missing; none, fixed, reference, external or recorded");
  Scenario::Controller c;
  c.kind = controllerKind(f, node["type"]);
  if (node["balance"]) f.check([&] { c.balance = f.boolean(node["balance"], "controller.balance"); });
  if (node["downforce_n"]) {
    c.downforce_n = positiveAtMost(f, node["downforce_n"], "controller.downforce_n", kMaxDownforceSetPoint_n);
  }
  if (node["valves"]) {
    const YAML::Node v = node["valves"];
    c.valves_line = YamlFields::lineOf(v);
    if (!v.IsSequence() || v.size() == 0 || v.size() > 24) {
      f.fail(v, "controller.valves", "it must be a list of openings in [0, 1], one per chamber of the robot");
    }
    for (std::size_t i = 0; i < v.size(); ++i) {
      c.valves.push_back(f.numberIn(v[i], "controller.valves[" + std::to_string(i) + "]", 0.0, 1.0));
    }
  }
  const bool uses_set_point = c.kind == Scenario::ControllerKind::kReference;
  if (node["valves"] && c.kind != Scenario::ControllerKind::kFixed) {
    f.fail(node["valves"], "controller.valves", "only a fixed controller takes valve openings");
  }
  if (!node["valves"] && c.kind == Scenario::ControllerKind::kFixed) {
    f.failKey(node, "controller.valves", "missing; a fixed controller needs one opening per chamber");
  }
  if (node["commands"]) {
    const std::string file = f.text(node["commands"], "controller.commands");
    if (file.empty()) f.fail(node["commands"], "controller.commands", "it must name a run.mcap");
    c.commands_file = resolveAgainst(source, file);
    if (c.kind != Scenario::ControllerKind::kRecorded) {
      f.fail(node["commands"], "controller.commands", "only a recorded controller takes recorded commands");
    }
  } else if (c.kind == Scenario::ControllerKind::kRecorded) {
    f.failKey(node, "controller.commands", "missing; a recorded controller needs the run.mcap it plays back");
  }
  if (node["downforce_n"] && !uses_set_point) {
    f.fail(node["downforce_n"], "controller.downforce_n", "only the reference controller takes a set-point");
  }
  return c;
}

/// `crack: {depth_m, width_m}`: only for the generated pylon, whose crack it changes.
Scenario::Crack parseCrack(const YamlFields& f, const YAML::Node& node, const std::string& scene_file) {
  f.requireMap(node, "crack", {"depth_m", "width_m"});
  Scenario::Crack c;
  if (node["depth_m"]) {
    f.check([&] { c.depth_m = positiveAtMost(f, node["depth_m"], "crack.depth_m", Scenario::Crack::kMaxDepth_m); });
  }
  if (node["width_m"]) {
    f.check([&] { c.width_m = positiveAtMost(f, node["width_m"], "crack.width_m", Scenario::Crack::kMaxWidth_m); });
  }
  if (!scene_file.empty() && scene_file != kGeneratedPylonScene) {
    f.fail(node, "crack",
           std::string("only the generated pylon (scene: ") + kGeneratedPylonScene + ") has this crack; scene is '" +
               YamlFields::shortText(scene_file) + "'");
  }
  return c;
}

// Entries after the end are kept and never reached, so that `--set duration_s=...` can shorten
// any scenario.
std::vector<Scenario::DriveCommand> parseDrive(const YamlFields& f, const YAML::Node& node) {
  if (!node.IsSequence() || node.size() == 0) {
    f.fail(node, "drive", "it must be a list of {t_s, vx_mps, vy_mps, wz_radps}, the first at t_s: 0");
  }
  std::vector<Scenario::DriveCommand> out;
  Scenario::DriveCommand held;
  for (std::size_t i = 0; i < node.size(); ++i) {
    const std::string key = "drive[" + std::to_string(i) + "]";
    const YAML::Node e = node[i];
    Scenario::DriveCommand cmd = held;
    bool ok = f.check([&] {
      f.requireMap(e, key, {"t_s", "vx_mps", "vy_mps", "wz_radps"});
      if (!e["t_s"]) f.failKey(e, key + ".t_s", "missing");
    });
    if (!ok) continue;
    ok &= f.check([&] {
      cmd.t_s = f.numberIn(e["t_s"], key + ".t_s", 0.0, kMaxTime_s);
      if (i == 0 && cmd.t_s != 0.0) f.fail(e["t_s"], key + ".t_s", "the first drive command must be at t_s: 0");
      if (!out.empty() && cmd.t_s <= out.back().t_s) f.fail(e["t_s"], key + ".t_s", "times must increase");
    });
    if (e["vx_mps"]) ok &= f.check([&] { cmd.vx_mps = f.numberIn(e["vx_mps"], key + ".vx_mps", -10.0, 10.0); });
    if (e["vy_mps"]) ok &= f.check([&] { cmd.vy_mps = f.numberIn(e["vy_mps"], key + ".vy_mps", -10.0, 10.0); });
    if (e["wz_radps"]) ok &= f.check([&] { cmd.wz_radps = f.numberIn(e["wz_radps"], key + ".wz_radps", -10.0, 10.0); });
    if (!ok) continue;
    out.push_back(cmd);
    held = cmd;
  }
  return out;
}

std::vector<Scenario::Fault> parseFaults(const YamlFields& f, const YAML::Node& node) {
  if (!node.IsSequence()) f.fail(node, "faults", "it must be a list of {t_s, kind, ...}");
  std::vector<Scenario::Fault> out;
  for (std::size_t i = 0; i < node.size(); ++i) {
    f.check([&] {
    const std::string key = "faults[" + std::to_string(i) + "]";
    const YAML::Node e = node[i];
    f.requireMap(e, key, {"t_s", "kind", "chamber", "opening", "engine"});
    if (!e["t_s"]) f.failKey(e, key + ".t_s", "missing");
    if (!e["kind"]) f.failKey(e, key + ".kind", "missing; valve_stuck or engine_failure");
    Scenario::Fault fault;
    fault.t_s = f.numberIn(e["t_s"], key + ".t_s", 0.0, kMaxTime_s);
    if (!out.empty() && fault.t_s < out.back().t_s) f.fail(e["t_s"], key + ".t_s", "faults must be in time order");
    const std::string kind = f.text(e["kind"], key + ".kind");
    if (kind == "valve_stuck") {
      fault.kind = Scenario::FaultKind::kValveStuck;
      if (!e["chamber"]) f.failKey(e, key + ".chamber", "missing; the chamber 1..7 whose valve sticks");
      if (!e["opening"]) f.failKey(e, key + ".opening", "missing; the opening it sticks at, in [0, 1]");
      if (e["engine"]) f.fail(e["engine"], key + ".engine", "a valve fault names no engine");
      fault.chamber = static_cast<int>(f.integer(e["chamber"], key + ".chamber", 1, 7));
      fault.opening = f.numberIn(e["opening"], key + ".opening", 0.0, 1.0);
    } else if (kind == "engine_failure") {
      fault.kind = Scenario::FaultKind::kEngineFailure;
      if (!e["engine"]) f.failKey(e, key + ".engine", "missing; the engine 1..N that fails");
      if (e["chamber"]) f.fail(e["chamber"], key + ".chamber", "an engine fault names no chamber");
      if (e["opening"]) f.fail(e["opening"], key + ".opening", "an engine fault has no opening");
      fault.engine = static_cast<int>(f.integer(e["engine"], key + ".engine", 1, 16));
    } else {
      f.fail(e["kind"], key + ".kind", "it must be valve_stuck or engine_failure");
    }
    out.push_back(fault);
    });
  }
  return out;
}

std::vector<double> parseTimes(const YamlFields& f, const YAML::Node& node, const std::string& key) {
  if (!node.IsSequence()) f.fail(node, key, "it must be a list of times in seconds");
  std::vector<double> out;
  for (std::size_t i = 0; i < node.size(); ++i) {
    const std::string k = key + "[" + std::to_string(i) + "]";
    f.check([&] { out.push_back(f.numberIn(node[i], k, 0.0, kMaxTime_s)); });
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

std::int64_t Scenario::depthPeriodSteps() const {
  return static_cast<std::int64_t>(std::llround(1e9 / (rates.depth_hz * static_cast<double>(step_ns))));
}

std::int64_t Scenario::laserPeriodSteps() const {
  return static_cast<std::int64_t>(std::llround(1e9 / (rates.laser_hz * static_cast<double>(step_ns))));
}

Scenario::DriveCommand driveCommandAt(const std::vector<Scenario::DriveCommand>& schedule, std::int64_t t_ns) {
  Scenario::DriveCommand current;
  for (const auto& cmd : schedule) {
    if (std::llround(cmd.t_s * 1e9) > t_ns) break;
    current = cmd;
  }
  return current;
}

std::string Scenario::robotPath() const {
  if (isShippedRobotName(robot_file)) return shippedRobotFile(robot_file);
  return resolveAgainst(source, robot_file);
}

std::string Scenario::scenePath(const std::string& build_dir) const {
  if (scene_file.rfind(kBuildPrefix, 0) == 0) {
    return (std::filesystem::path(build_dir) / scene_file.substr(std::string(kBuildPrefix).size()))
        .lexically_normal()
        .string();
  }
  return resolveAgainst(source, scene_file);
}

namespace {
Scenario parseScenarioRoot(YAML::Node root, const std::string& source);

/// After `--set controller.type=T`: the controller keys of the file that T does not take are
/// removed from `root`, a line each returned. Keys that an override sets stay (and fail).
std::vector<std::string> dropKeysOfReplacedController(YAML::Node& root, const std::vector<std::string>& overrides,
                                                      const std::string& source) {
  std::vector<std::string> notes;
  const auto overridden = [&](const std::string& key) {
    return std::any_of(overrides.begin(), overrides.end(), [&](const std::string& o) { return o.rfind(key + "=", 0) == 0; });
  };
  if (!overridden("controller.type")) return notes;
  YAML::Node controller = root["controller"];
  if (!controller.IsMap() || !controller["type"].IsScalar()) return notes;  // reported by the validation
  const std::string type = controller["type"].Scalar();
  struct Key {
    const char* name;
    const char* taken_by;
    const char* what;
  };
  for (const Key& key : {Key{"downforce_n", "reference", "set-point"}, Key{"valves", "fixed", "valve openings"},
                         Key{"commands", "recorded", "recorded commands"}}) {
    if (type == key.taken_by || !controller[key.name] || overridden(std::string("controller.") + key.name)) continue;
    const YAML::Node value = controller[key.name];
    const int line = YamlFields::lineOf(value);
    notes.push_back(source + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": controller." + key.name +
                    " = " + YamlFields::show(value) +
                    " is ignored: --set controller.type=" +
                    YamlFields::shortText(type) + " takes no " + key.what + " (only a " + key.taken_by +
                    " controller does)");
    controller.remove(key.name);
  }
  return notes;
}
}  // namespace

Scenario parseScenarioText(const std::string& yaml_text, const std::string& source,
                           const std::vector<std::string>& overrides) {
  YAML::Node root = YamlFields::load(yaml_text, source);
  if (!root.IsDefined() || root.IsNull()) throw ConfigError(source + ": the file is empty");
  for (const auto& o : overrides) applyOverride(root, o);
  std::vector<std::string> ignored = dropKeysOfReplacedController(root, overrides, source);
  try {
    Scenario scenario = parseScenarioRoot(root, source);
    scenario.ignored = std::move(ignored);
    return scenario;
  } catch (const ConfigError& e) {
    // A value that came from --set has no line in the file: name the override instead.
    const std::string text = e.what();
    std::string out;
    for (std::size_t begin = 0; begin <= text.size();) {
      const std::size_t end = std::min(text.find('\n', begin), text.size());
      std::string message = text.substr(begin, end - begin);
      bool replaced = false;
      for (const auto& o : overrides) {
        const std::string key = o.substr(0, o.find('='));
        std::vector<std::string> tails = {": " + key + " =", ": " + key + ".", ": " + key + "[", ": " + key + ":"};
        // A mapping that --set created or changed (`crack` of `--set crack.depth_m=...`).
        for (auto dot = key.rfind('.'); dot != std::string::npos && dot > 0; dot = key.rfind('.', dot - 1)) {
          tails.push_back(": " + key.substr(0, dot) + " =");
        }
        for (const std::string& tail : tails) {
          const auto at = message.find(tail);
          if (!replaced && at != std::string::npos) {
            message = source + " (--set " + YamlFields::shortText(o) + ")" + message.substr(at);
            replaced = true;
          }
        }
      }
      out += (out.empty() ? "" : "\n") + message;
      begin = end + 1;
    }
    throw ConfigError(out);
  }
}

namespace {
/// Where a scenario may put the robot, in the wall frame [m]: any real pylon is smaller.
constexpr double kMaxPosition_m = 1000.0;
/// Longest scenario [s].
constexpr double kMaxDuration_s = 86400.0;
/// Highest rate of any schedule [Hz].
constexpr double kMaxRate_hz = 1e6;

Scenario parseScenarioRoot(YAML::Node root, const std::string& source) {
  const YamlFields f(source);
  f.requireMap(root, "",
               {"name", "robot", "scene", "crack", "start", "wall", "duration_s", "step_ms", "rates", "depth_camera",
                "controller", "drive", "faults", "pictures", "recording", "seed", "end_on", "slide_limit_m"});
  for (const char* required : {"name", "robot", "scene", "start", "duration_s", "controller", "drive"}) {
    if (!root[required]) f.check([&] { f.failKey(root, required, "missing"); });
  }
  Scenario s;
  s.source = source;
  if (root["name"]) f.check([&] { s.name = f.text(root["name"], "name"); });
  if (root["robot"]) {
    s.robot_line = YamlFields::lineOf(root["robot"]);
    f.check([&] { s.robot_file = f.text(root["robot"], "robot"); });
  }
  if (root["scene"]) f.check([&] { s.scene_file = f.text(root["scene"], "scene"); });
  if (root["crack"]) f.check([&] { s.crack = parseCrack(f, root["crack"], s.scene_file); });

  const YAML::Node start = root["start"];
  if (start) {
    f.check([&] {
      f.requireMap(start, "start", {"x_m", "y_m", "yaw_deg", "hold_s"});
      for (const char* k : {"x_m", "y_m"}) {
        if (!start[k]) f.check([&] { f.failKey(start, std::string("start.") + k, "missing"); });
      }
      if (start["x_m"]) f.check([&] { s.start.x_m = f.numberIn(start["x_m"], "start.x_m", -kMaxPosition_m, kMaxPosition_m); });
      if (start["y_m"]) f.check([&] { s.start.y_m = f.numberIn(start["y_m"], "start.y_m", -kMaxPosition_m, kMaxPosition_m); });
      if (start["yaw_deg"]) f.check([&] { s.start.yaw_deg = f.numberIn(start["yaw_deg"], "start.yaw_deg", -360.0, 360.0); });
      // A hold longer than the run holds the robot for the whole run: harmless (e.g. a
      // shortened check run), so only the range is checked.
      if (start["hold_s"]) f.check([&] { s.start.hold_s = f.numberIn(start["hold_s"], "start.hold_s", 0.0, kMaxDuration_s); });
    });
  }

  if (root["wall"]) f.check([&] { s.wall = parseWall(f, root["wall"]); });
  if (root["duration_s"]) {
    f.check([&] {
      s.duration_s = f.positive(root["duration_s"], "duration_s");
      if (s.duration_s > kMaxDuration_s) f.fail(root["duration_s"], "duration_s", "it must be at most one day (86400)");
    });
  }
  bool step_ok = true;
  if (root["step_ms"]) {
    step_ok = f.check([&] {
      const double step_ms = f.positive(root["step_ms"], "step_ms");
      const double step_ns = std::round(step_ms * 1e6);
      if (step_ns < 1e5 || step_ns > 1e9 || std::abs(step_ns - step_ms * 1e6) > 1e-6 * step_ns) {
        f.fail(root["step_ms"], "step_ms", "it must be whole nanoseconds between 0.1 and 1000 ms");
      }
      s.step_ns = static_cast<std::int64_t>(step_ns);
    });
  }
  if (root["rates"]) {
    const YAML::Node r = root["rates"];
    f.check([&] {
      f.requireMap(r, "rates", {"drive_hz", "depth_hz", "laser_hz"});
      bool ok = true;
      if (r["drive_hz"]) ok &= f.check([&] { s.rates.drive_hz = positiveAtMost(f, r["drive_hz"], "rates.drive_hz", kMaxRate_hz); });
      if (r["depth_hz"]) ok &= f.check([&] { s.rates.depth_hz = positiveAtMost(f, r["depth_hz"], "rates.depth_hz", kMaxRate_hz); });
      if (r["laser_hz"]) ok &= f.check([&] { s.rates.laser_hz = positiveAtMost(f, r["laser_hz"], "rates.laser_hz", kMaxRate_hz); });
      if (!ok || !step_ok) return;  // the relations need valid numbers
      // The drive substeps inside a step: at least one substep, a whole number of them.
      const double substeps = s.rates.drive_hz * static_cast<double>(s.step_ns) / 1e9;
      if (r["drive_hz"] && (substeps < 1.0 - 1e-9 || std::abs(substeps - std::round(substeps)) > 1e-9 * substeps)) {
        f.check([&] {
          f.fail(r["drive_hz"], "rates.drive_hz", "it must be a whole multiple of the lockstep rate (1000 / step_ms)");
        });
      }
      f.check([&] { periodSteps(f, r["depth_hz"] ? r["depth_hz"] : r, "rates.depth_hz", s.rates.depth_hz, s.step_ns); });
      f.check([&] { periodSteps(f, r["laser_hz"] ? r["laser_hz"] : r, "rates.laser_hz", s.rates.laser_hz, s.step_ns); });
    });
  } else if (step_ok) {
    f.check([&] { periodSteps(f, root, "rates.depth_hz", s.rates.depth_hz, s.step_ns); });
    f.check([&] { periodSteps(f, root, "rates.laser_hz", s.rates.laser_hz, s.step_ns); });
  }
  if (root["depth_camera"]) {
    const YAML::Node d = root["depth_camera"];
    f.check([&] {
      f.requireMap(d, "depth_camera", {"size_px", "subpixel"});
      if (d["size_px"]) {
        f.check([&] { s.depth_camera.size_px = static_cast<int>(f.integer(d["size_px"], "depth_camera.size_px", 1, Scenario::DepthCamera::kMaxSizePx)); });
      }
      if (d["subpixel"]) f.check([&] { s.depth_camera.subpixel = f.boolean(d["subpixel"], "depth_camera.subpixel"); });
    });
  }
  if (root["controller"]) f.check([&] { s.controller = parseController(f, root["controller"], source); });
  if (root["drive"]) f.check([&] { s.drive = parseDrive(f, root["drive"]); });
  if (root["faults"]) f.check([&] { s.faults = parseFaults(f, root["faults"]); });
  if (root["end_on"]) {
    const YAML::Node e = root["end_on"];
    f.check([&] {
      f.requireMap(e, "end_on", {"fall", "seal_over_nothing"});
      if (e["fall"]) f.check([&] { s.end_on.fall = f.boolean(e["fall"], "end_on.fall"); });
      if (e["seal_over_nothing"]) {
        f.check([&] { s.end_on.seal_over_nothing = f.boolean(e["seal_over_nothing"], "end_on.seal_over_nothing"); });
      }
    });
  }
  if (root["pictures"]) {
    const YAML::Node p = root["pictures"];
    f.check([&] {
      f.requireMap(p, "pictures", {"sealing_at_s", "ring_at_s"});
      if (p["sealing_at_s"]) f.check([&] { s.pictures.sealing_at_s = parseTimes(f, p["sealing_at_s"], "pictures.sealing_at_s"); });
      if (p["ring_at_s"]) f.check([&] { s.pictures.ring_at_s = parseTimes(f, p["ring_at_s"], "pictures.ring_at_s"); });
    });
  }
  if (root["recording"]) {
    const YAML::Node r = root["recording"];
    f.check([&] {
      f.requireMap(r, "recording", {"depth_images", "commands"});
      if (r["depth_images"]) f.check([&] { s.recording.depth_images = f.boolean(r["depth_images"], "recording.depth_images"); });
      if (r["commands"]) f.check([&] { s.recording.commands = f.boolean(r["commands"], "recording.commands"); });
    });
  }
  if (root["seed"]) f.check([&] { s.seed = static_cast<std::uint64_t>(f.integer(root["seed"], "seed", 0, (1LL << 53))); });
  if (root["slide_limit_m"]) {
    f.check([&] { s.slide_limit_m = positiveAtMost(f, root["slide_limit_m"], "slide_limit_m", 10.0); });
  }
  f.finish();
  return s;
}
}  // namespace

namespace {
/// `value` in the fewest digits that read back as the same double ("0.005", not 0.00500...01).
std::string shortestNumber(double value) {
  char text[32];
  const auto result = std::to_chars(text, text + sizeof text, value);
  return std::string(text, result.ptr);
}

std::string readScenarioFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw ConfigError(path + ": cannot read the scenario file");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}
}  // namespace

Scenario loadScenario(const std::string& path, const std::vector<std::string>& overrides) {
  return parseScenarioText(readScenarioFile(path), path, overrides);
}

std::string resolvedScenarioText(const std::string& path, const std::vector<std::string>& overrides,
                                 const std::string& build_dir, const std::string& run_scene) {
  const std::string text = readScenarioFile(path);
  const Scenario scenario = parseScenarioText(text, path, overrides);
  if (scenario.crack.has_value() == run_scene.empty()) {
    throw ConfigError(path + ": " +
                      (run_scene.empty() ? std::string("crack is set, but no scene was generated for the run")
                                         : "a scene was generated for the run, but crack is not set"));
  }
  YAML::Node root = YAML::Load(text);
  for (const auto& o : overrides) applyOverride(root, o);
  dropKeysOfReplacedController(root, overrides, path);  // noted in scenario.ignored
  root["robot"] = std::filesystem::absolute(scenario.robotPath()).lexically_normal().string();
  if (!scenario.controller.commands_file.empty()) {
    root["controller"]["commands"] = std::filesystem::absolute(scenario.controller.commands_file).lexically_normal().string();
  }
  std::string note;
  if (scenario.crack) {
    root.remove("crack");
    root["scene"] = std::filesystem::absolute(run_scene).lexically_normal().string();
    note = "# crack: {depth_m: " + shortestNumber(scenario.crack->depth_m) +
           ", width_m: " + shortestNumber(scenario.crack->width_m) + "}: the pylon generated for this run (scene)\n";
  } else {
    root["scene"] = std::filesystem::absolute(scenario.scenePath(build_dir)).lexically_normal().string();
  }
  YAML::Emitter out;
  out << root;
  return std::string("# Resolved from ") + std::filesystem::absolute(path).lexically_normal().string() + "\n" + note +
         out.c_str() + "\n";
}

const char* toString(Scenario::ControllerKind kind) {
  switch (kind) {
    case Scenario::ControllerKind::kNone: return "none";
    case Scenario::ControllerKind::kFixed: return "fixed";
    case Scenario::ControllerKind::kReference: return "reference";
    case Scenario::ControllerKind::kExternal: return "external";
    case Scenario::ControllerKind::kRecorded: return "recorded";
  }
  return "?";
}

const char* toString(Scenario::WallKind kind) {
  switch (kind) {
    case Scenario::WallKind::kVertical: return "vertical";
    case Scenario::WallKind::kFloor: return "floor";
    case Scenario::WallKind::kOverhang: return "overhang";
  }
  return "?";
}

}  // namespace climbsim
