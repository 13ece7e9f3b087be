#include "depth_layout_check.hpp"

#include <filesystem>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "climbsim/errors.hpp"
#include "climbsim/shard_tiles/depth_grid.hpp"
#include "climbsim/shard_tiles/shard_partition.hpp"
#include "climbsim/yaml_fields.hpp"
#include "scene/configure.hpp"
#include "sealing/configure.hpp"

namespace climbsim::launcher {
namespace {

namespace fs = std::filesystem;

/// Every value of `option` in `argv` (`--option VALUE` or `--option=VALUE`), comma lists split.
std::vector<std::string> optionValues(const std::vector<std::string>& argv, const std::string& option) {
  std::vector<std::string> values;
  const auto add = [&](const std::string& text) {
    std::stringstream list(text);
    for (std::string item; std::getline(list, item, ',');) {
      if (!item.empty()) values.push_back(item);
    }
  };
  for (std::size_t i = 1; i < argv.size(); ++i) {
    if (argv[i] == option && i + 1 < argv.size()) add(argv[i + 1]);
    if (argv[i].rfind(option + "=", 0) == 0) add(argv[i].substr(option.size() + 1));
  }
  return values;
}

std::optional<std::string> optionValue(const std::vector<std::string>& argv, const std::string& option) {
  const auto values = optionValues(argv, option);
  if (values.empty()) return std::nullopt;
  return values.back();  // CLI11 keeps the last of a repeated single-value option
}

bool hasOption(const std::vector<std::string>& argv, const std::string& option) {
  for (std::size_t i = 1; i < argv.size(); ++i) {
    if (argv[i] == option || argv[i].rfind(option + "=", 0) == 0) return true;
  }
  return false;
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
  return text;
}

/// One instance of a climbsim-scene or climbsim-sealing service.
struct Instance {
  std::string name;   ///< roster name
  std::string where;  ///< "<compose>:<line>: services.<name> (<instance>)"
  std::string entry;  ///< "services.<name>, line <line>"
  std::vector<std::string> argv;
};

std::vector<Instance> instancesOf(const ComposeFile& compose, const std::string& program) {
  std::vector<Instance> found;
  for (const auto& service : compose.services) {
    if (service.command.empty() || fs::path(service.command.front()).filename() != program) continue;
    const auto names = service.instanceNames();
    for (std::size_t replica = 0; replica < names.size(); ++replica) {
      Instance instance;
      instance.name = names[replica];
      instance.where = compose.source + ":" + std::to_string(service.line) + ": services." + service.name +
                       (names.size() > 1 ? " (" + names[replica] + ")" : "");
      instance.entry = "services." + service.name + ", line " + std::to_string(service.line);
      for (const auto& arg : service.command) {
        instance.argv.push_back(replaced(replaced(arg, "${replicas}", std::to_string(names.size())), "${replica}",
                                         std::to_string(replica)));
      }
      found.push_back(std::move(instance));
    }
  }
  return found;
}

double number(const Instance& instance, const std::string& option, const std::string& text) {
  try {
    std::size_t used = 0;
    const double value = std::stod(text, &used);
    if (used == text.size()) return value;
  } catch (const std::exception&) {
  }
  throw ConfigError(instance.where + ": " + option + " = " + YamlFields::shortText(text) + ": not a number");
}

/// A depth renderer: its image and the tile it renders ("" for the whole image).
struct Renderer {
  const Instance* instance = nullptr;
  sealing::PixelGrid grid;
  std::string tile;
};

std::string gridText(const sealing::PixelGrid& grid) {
  std::ostringstream text;
  text.precision(6);
  text << grid.width_px << " x " << grid.height_px << " px of " << grid.pixel_size_m * 1e3 << " mm";
  return text.str();
}

/// The scenario and robot an instance configures itself from, as its main loads them: the run's
/// with --scenario, else none and the robot of --robot, else the default robot.
ScenarioAndRobot runOf(const Instance& instance, const Scenario& scenario) {
  if (hasOption(instance.argv, "--scenario")) return scenarioAndRobot(scenario);
  try {
    return loadScenarioAndRobot("", {}, optionValue(instance.argv, "--robot").value_or(""));
  } catch (const ConfigError& e) {
    throw ConfigError(instance.where + ": " + e.what());
  }
}

Renderer rendererOf(const Instance& instance, const Scenario& scenario, const scene::SceneDescription& description) {
  // As climbsim-scene configures it (scene/configure.hpp) from the options that set the image.
  scene::SceneOverrides overrides;
  overrides.camera = optionValue(instance.argv, "--camera");
  if (const auto px = optionValue(instance.argv, "--depth-size-px")) {
    overrides.depth_size_px = static_cast<int>(number(instance, "--depth-size-px", *px));
  }
  if (const auto m = optionValue(instance.argv, "--depth-width-m")) {
    overrides.depth_width_m = number(instance, "--depth-width-m", *m);
  }
  scene::DepthCameraParams camera;
  try {
    camera = scene::depthCameraParams(description, scene::sceneParams(runOf(instance, scenario), overrides));
  } catch (const ConfigError& e) {
    throw ConfigError(instance.where + ": " + e.what());
  }
  return Renderer{&instance, sealing::PixelGrid{camera.width_px, camera.height_px, camera.pixel_size_m},
                  optionValue(instance.argv, "--tile").value_or("")};
}

}  // namespace

void checkDepthLayout(const ComposeFile& compose, const Scenario& scenario, const scene::SceneDescription& description) {
  const auto scenes = instancesOf(compose, "climbsim-scene");
  std::vector<Renderer> renderers;
  for (const auto& instance : scenes) {
    if (hasOption(instance.argv, "--scene")) continue;  // a scene of its own
    const std::string outputs = optionValue(instance.argv, "--outputs").value_or("depth,laser");
    if (outputs.find("depth") == std::string::npos) continue;
    renderers.push_back(rendererOf(instance, scenario, description));
  }
  std::set<std::string> instances;
  for (const auto& service : compose.services) {
    for (const auto& name : service.instanceNames()) instances.insert(name);
  }
  const auto shards = instancesOf(compose, "climbsim-sealing");
  for (const auto& shard : shards) {
    if (hasOption(shard.argv, "--offline")) continue;
    // As climbsim-sealing configures it (sealing/configure.hpp).
    sealing::SealingOverrides overrides;
    if (const auto text = optionValue(shard.argv, "--camera-px")) {
      overrides.camera_px = static_cast<int>(number(shard, "--camera-px", *text));
    }
    if (const auto text = optionValue(shard.argv, "--view-m")) overrides.view_m = number(shard, "--view-m", *text);
    if (const auto text = optionValue(shard.argv, "--shard")) overrides.shard = *text;
    sealing::PixelGrid grid;
    sealing::ShardSpec spec;
    try {
      grid = sealing::sealingCamera(runOf(shard, scenario), overrides);
      spec = sealing::ShardSpec::parse(overrides.shard);
    } catch (const ConfigError& e) {
      throw ConfigError(shard.where + ": " + e.what());
    }

    std::vector<const Renderer*> read;
    const auto from = optionValues(shard.argv, "--depth-from");
    bool other_producer = false;
    for (const auto& name : from) {
      const Renderer* match = nullptr;
      for (const auto& renderer : renderers) {
        if (renderer.instance->name == name) match = &renderer;
      }
      if (match == nullptr && instances.count(name) > 0) {
        other_producer = true;  // not a climbsim-scene: the clock checks that it writes depth images
        continue;
      }
      if (match == nullptr) {
        std::string names;
        for (const auto& renderer : renderers) names += (names.empty() ? "" : ", ") + renderer.instance->name;
        throw ConfigError(shard.where + ": --depth-from " + YamlFields::shortText(name) +
                          ": no service instance of this compose file has that name (depth renderers: " +
                          (names.empty() ? "none" : names) + ")");
      }
      read.push_back(match);
    }
    if (from.empty()) {
      for (const auto& renderer : renderers) read.push_back(&renderer);
    }
    // No renderer at all, or a producer of another program: the clock names a missing one.
    if (read.empty() || other_producer) continue;

    for (const Renderer* renderer : read) {
      const std::string why = sealing::checkPixelGrid(renderer->grid, grid);
      if (!why.empty()) {
        throw ConfigError(shard.where + ": reads a depth image of " + gridText(grid) + " (--camera-px, --view-m, " +
                          "or the scenario's depth_camera.size_px), but '" + renderer->instance->name + "' (" +
                          renderer->instance->entry + ") renders " +
                          gridText(renderer->grid) + ": the shards and the renderers must agree on the image");
      }
    }
    bool covered = false;
    std::string seen;
    for (const Renderer* renderer : read) {
      if (renderer->tile.empty()) {
        covered = true;
        break;
      }
      sealing::ShardSpec tile;
      try {
        tile = sealing::ShardSpec::parse(renderer->tile);
      } catch (const ConfigError&) {
        throw ConfigError(renderer->instance->where + ": --tile = '" + YamlFields::shortText(renderer->tile) +
                          "': expected I/N with 0 <= I < N, e.g. 0/2");
      }
      // Tile 0/1 is every sealing pixel's box: it holds any shard's region.
      if (tile.count == 1 || (tile.index == spec.index && tile.count == spec.count)) {
        covered = true;
        break;
      }
      seen += (seen.empty() ? "" : ", ") + renderer->instance->name + " --tile " + renderer->tile;
    }
    if (!covered) {
      throw ConfigError(shard.where + ": shard " + overrides.shard + " reads " + seen + ": none renders tile " +
                        overrides.shard + " or the whole image (run one climbsim-scene --tile I/N per shard I/N, e.g. --tile "
                        "\"${replica}/${replicas}\" with as many replicas as the shards)");
    }
  }
}

}  // namespace climbsim::launcher
