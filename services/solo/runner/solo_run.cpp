#include "solo_run.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <future>
#include <memory>
#include <optional>
#include <algorithm>
#include <cstdlib>

#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "climbsim/errors.hpp"
#include "climbsim/realtime_text.hpp"
#include "climbsim/robot/robot_description.hpp"
#include "climbsim/robot/robot_geometry.hpp"
#include "climbsim/scenario.hpp"
#include "climbsim/schedule.hpp"
#include "drive/model/params_from_robot.hpp"
#include "controller_node.hpp"
#include "drive_node.hpp"
#include "drive_translate.hpp"
#include "wheels_over_scene.hpp"
#include "picture_schedule.hpp"
#include "node/run_summary.hpp"
#include "scene_node.hpp"
#include "scene_translate.hpp"
#include "sealing_node.hpp"
#include "node/sealing_picture_files.hpp"
#include "thermo_node.hpp"
#include "thermo_translate.hpp"
#include "node/trace_recorder.hpp"
#include "climbsim/run_prep/run_scene.hpp"
#include "climbsim/wall/scene_xml.hpp"
#include "climbsim/shard_tiles/sealing_params.hpp"
#include "sealing_translate.hpp"
#include "stamped_bus.hpp"
#include "thermo/model/params_from_robot.hpp"

namespace climbsim::solo {
namespace {
namespace fs = std::filesystem;

/// The participant names of the default composition (deploy/compose.yaml; one replica each).
constexpr const char* kScene = "scene";
constexpr const char* kSealing = "sealing";
constexpr const char* kThermo = "thermo";
constexpr const char* kDrive = "drive";
constexpr const char* kController = "controller";

drive::WallOrientation wallFromScenario(const Scenario::Wall& wall) {
  switch (wall.kind) {
    case Scenario::WallKind::kFloor: return drive::WallOrientation::floor();
    case Scenario::WallKind::kOverhang: return drive::WallOrientation::overhang(wall.overhang_deg);
    case Scenario::WallKind::kVertical: break;
  }
  return drive::WallOrientation::vertical();
}

/// The clock's step as `climbsim-clock --step-ms` makes it from the launcher's number.
std::int64_t clockStepNs(const Scenario& scenario) {
  const double step_ms = static_cast<double>(scenario.step_ns) * 1e-6;
  return static_cast<std::int64_t>(std::round(step_ms * 1e6));
}

/// The clock's end step as `climbsim-clock --duration-s` makes it.
std::uint64_t clockEndStep(const Scenario& scenario, std::int64_t dt_ns) {
  return static_cast<std::uint64_t>(std::llround(scenario.duration_s * 1e9 / static_cast<double>(dt_ns)));
}

/// summary.json's wheels_over_nothing as the launcher writes it from the drive's lines
/// (fallback_summary.hpp addWheelsOverNothing): {first_at_s, wheels: [N, ...]}, the time as the
/// line gives it (3 decimals).
void noteWheelOverNothing(nlohmann::json& entry, int wheel, std::int64_t t_ns) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f", static_cast<double>(t_ns) * 1e-9);
  const double at_s = std::strtod(text, nullptr);
  if (entry.is_null()) entry = {{"first_at_s", at_s}, {"wheels", nlohmann::json::array()}};
  entry["first_at_s"] = std::min(entry["first_at_s"].get<double>(), at_s);
  entry["wheels"].push_back(wheel);  // each wheel is named once (WheelsOverScene)
}

void writeFile(const fs::path& path, const std::vector<unsigned char>& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (!out) spdlog::warn("solo: cannot write {}", path.string());
}

}  // namespace

SoloResult runSolo(const SoloOptions& options) {
  // The run directory as the launcher prepares it: the resolved scenario every service reads.
  fs::create_directories(options.out_dir);
  // Keys an override made meaningless (--set controller.type=none on a set-point): said once.
  for (const auto& note : loadScenario(options.scenario_file, options.overrides).ignored) spdlog::warn("{}", note);
  const std::string text =
      surface::runScenarioText(options.scenario_file, options.overrides, options.build_dir, options.out_dir);
  const std::string scenario_file = (fs::path(options.out_dir) / "scenario.yaml").string();
  for (const char* stale : {"trace.csv", "summary.json"}) fs::remove(fs::path(options.out_dir) / stale);
  {
    std::ofstream out(scenario_file, std::ios::trunc);
    out << text;
    if (!out) throw ConfigError(scenario_file + ": cannot write (--out " + options.out_dir + ")");
  }
  const Scenario scenario = loadScenario(scenario_file);
  if (scenario.controller.kind == Scenario::ControllerKind::kExternal) {
    throw ConfigError(options.scenario_file + ": controller.type = external: a solo run has no DDS, so no external "
                      "controller can join it; use `climbsim run` (or another controller type)");
  }
  const RobotDescription robot = loadRobotDescription(scenario.robotPath());
  const RobotGeometry geometry = computeGeometry(robot);

  const std::int64_t dt_ns = clockStepNs(scenario);
  const std::uint64_t end_step = clockEndStep(scenario, dt_ns);
  const auto depth_period = static_cast<std::uint32_t>(scenario.depthPeriodSteps());
  const Schedule every_step{1, 0};
  const Schedule scene_schedule{depth_period, 0};
  const Schedule sealing_schedule{depth_period, 1 % depth_period};
  scene_schedule.validate("scene");
  sealing_schedule.validate("sealing");

  // The drive service's check of the wheels against the scene (summary.json's
  // wheels_over_nothing), loaded while the models are, as the drive loads it while joining.
  std::future<std::optional<drive::WheelsOverScene>> wheel_check_loading =
      std::async(std::launch::async, [&] {
        return drive::wheelCheckOnScene(scenario.scenePath(options.build_dir),
                                        drive::driveParamsFromRobot(robot, geometry).wheels);
      });

  // --- the models behind their nodes, configured as each service's main() does
  scene::SceneNodeOptions scene_options;
  scene_options.laser.clear();  // compose.yaml: --outputs depth
  if (scenario.depth_camera.size_px > 0) scene_options.depth_size_px = scenario.depth_camera.size_px;
  scene::SceneNode scene_node(scene::loadScene(scenario.scenePath(options.build_dir)), scene_options);

  // climbsim-sealing's --camera-px (the scenario's depth_camera.size_px, else 256) and --view-m.
  const int camera_px = scenario.depth_camera.size_px > 0 ? scenario.depth_camera.size_px : 256;
  const sealing::PixelGrid camera{camera_px, camera_px, 0.80 / camera_px};
  const sealing::SealingModel sealing_model(sealing::sealingParamsFromRobot(robot, geometry), geometry, camera,
                                            scenario.robotPath());
  sealing::SealingNode sealing_node(sealing_model, sealing::ShardSpec{0, 1});
  sealing::PictureSchedule picture_schedule(scenario.pictures.sealing_at_s);

  thermo::ThermoParams thermo_params = thermo::thermoParamsFromRobot(robot, geometry);
  thermo_params.faults = thermo::plantFaultsFromScenario(scenario.faults, scenario.source, thermo_params.engines.size());
  thermo::ThermoNode thermo_node(std::move(thermo_params), thermo::segmentNames(geometry),
                                 thermo::basicLeakAreas(robot, geometry));

  drive::DriveParams drive_params = drive::driveParamsFromRobot(robot, geometry);
  drive_params.substep_s = 1.0 / scenario.rates.drive_hz;
  drive::DriveNode drive_node(drive_params, wallFromScenario(scenario.wall),
                              drive::StartPose{scenario.start.x_m, scenario.start.y_m,
                                               scenario.start.yaw_deg * 3.14159265358979323846 / 180.0},
                              drive::kAdhesionForceBeforeThermo_n);
  drive_node.holdUntil(std::llround(scenario.start.hold_s * 1e9));

  nlohmann::json wheels_over_nothing = nullptr;

  controller::ControllerNode controller_node(controller::controllerParams(scenario, robot, geometry));

  recorder::TraceRecorder recorder(thermo::segmentNames(geometry), thermo::basicLeakAreas(robot, geometry),
                                   static_cast<int>(geometry.wheels.size()));
  recorder.setSlideLimit(scenario.slide_limit_m);
  recorder.setDownforceFrom(std::llround(scenario.start.hold_s * 1e9));
  std::optional<recorder::SealingPictureFiles> picture_files;
  const fs::path pictures_dir = fs::path(options.out_dir) / "pictures";
  if (!scenario.pictures.sealing_at_s.empty()) {
    fs::create_directories(pictures_dir);
    picture_files.emplace(scenario.pictures.sealing_at_s);
  }

  // --- the topics, with the producers the roster has
  StampedTopic<climbsim::RobotState> robot_state(scene::topic::kRobotState);
  StampedTopic<climbsim::DriveState> drive_state(drive::topic::kDriveState);
  StampedTopic<climbsim::DepthImage> depth_image(scene::topic::kDepthImage);
  StampedTopic<climbsim::Leakage> leakage(sealing::topic::kLeakage);
  StampedTopic<climbsim::ChamberState> chamber_state(thermo::topic::kChamberState);
  StampedTopic<climbsim::AdhesionForce> adhesion(thermo::topic::kAdhesionForce);
  StampedTopic<climbsim::ValveCommand> valve_command(thermo::topic::kValveCommand);
  StampedTopic<climbsim::EngineCommand> engine_command(thermo::topic::kEngineCommand);
  StampedTopic<climbsim::DriveCommand> drive_command(drive::topic::kDriveCommand);
  robot_state.addProducer(kDrive, every_step);
  drive_state.addProducer(kDrive, every_step);
  depth_image.addProducer(kScene, scene_schedule);
  leakage.addProducer(kSealing, sealing_schedule);
  chamber_state.addProducer(kThermo, every_step);
  adhesion.addProducer(kThermo, every_step);
  if (controller_node.commandsValves()) valve_command.addProducer(kController, every_step);
  engine_command.addProducer(kController, every_step);
  drive_command.addProducer(kController, every_step);

  // The producers' states before step 0, as each service's main() records them: row 0.
  {
    const auto initial = thermo_node.initialOutputs();
    chamber_state.setInitial(kThermo, thermo::chamberStateToIdl(initial));
    adhesion.setInitial(kThermo, thermo::adhesionForceToIdl(initial));
    robot_state.setInitial(kDrive, drive::robotStateToIdl(drive_node.initialOutputs()));
    drive_state.setInitial(kDrive, drive::driveStateToIdl(drive_node.initialOutputs()));
  }

  const std::string trace_path = (fs::path(options.out_dir) / "trace.csv").string();
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> trace(std::fopen(trace_path.c_str(), "w"), &std::fclose);
  if (!trace) throw ConfigError(trace_path + ": cannot write (--out " + options.out_dir + ")");
  std::string header;
  for (const auto& c : recorder.columns()) header += (header.empty() ? "" : ",") + c;
  std::fprintf(trace.get(), "%s\n", header.c_str());

  std::optional<drive::WheelsOverScene> wheel_check = wheel_check_loading.get();

  SoloResult result;
  result.outcome = "completed";
  result.reason = "end of run after " + std::to_string(end_step) + " steps";
  std::optional<std::string> fell_reason;
  std::optional<std::string> seal_failure;  ///< end_on.seal_over_nothing: the run fails
  const auto started = std::chrono::steady_clock::now();
  // Every input is read with a one-step lag, so the order of the participants inside a step
  // changes nothing; this is the order of the loop (DESIGN.md §1).
  for (std::uint64_t k = 0; k < end_step; ++k) {
    if (options.stop != nullptr && options.stop->load()) {
      result.outcome = "stopped";
      result.reason = k > 0 ? "stopped on request after step " + std::to_string(k - 1) : "stopped on request before step 0";
      result.exit_code = kExitStopped;
      break;
    }
    const std::int64_t t_ns = static_cast<std::int64_t>(k) * dt_ns;

    {  // controller (climbsim-controller's step)
      auto commands = controller_node.step(t_ns, dt_ns, chamber_state.get(k, Lag::kOneStep),
                                           adhesion.get(k, Lag::kOneStep));
      if (commands.valves) valve_command.write(kController, k, t_ns, *commands.valves);
      engine_command.write(kController, k, t_ns, commands.engines);
      drive_command.write(kController, k, t_ns, commands.drive);
    }
    {  // thermo
      const auto outputs = thermo_node.step(t_ns, dt_ns, leakage.get(k, Lag::kOneStep),
                                            valve_command.get(k, Lag::kOneStep), engine_command.get(k, Lag::kOneStep));
      chamber_state.write(kThermo, k, t_ns, thermo::chamberStateToIdl(outputs));
      auto force = thermo::adhesionForceToIdl(outputs);
      force.downforce_setpoint_n(thermo_node.downforceSetpoint());
      adhesion.write(kThermo, k, t_ns, std::move(force));
    }
    {  // drive
      const auto& outputs =
          drive_node.step(t_ns, dt_ns, drive_command.get(k, Lag::kOneStep), adhesion.get(k, Lag::kOneStep));
      robot_state.write(kDrive, k, t_ns, drive::robotStateToIdl(outputs));
      drive_state.write(kDrive, k, t_ns, drive::driveStateToIdl(outputs));
      if (wheel_check) {
        for (const std::size_t w : wheel_check->newlyOverNothing(outputs)) {
          spdlog::warn("solo: {}", wheel_check->overNothingText(outputs, w, t_ns + dt_ns));
          noteWheelOverNothing(wheels_over_nothing, static_cast<int>(w) + 1, t_ns + dt_ns);
        }
      }
      if (outputs.fell && !fell_reason) {
        const auto& p = outputs.position_m;
        const auto& v = outputs.linear_velocity_mps;
        char reason[200];
        std::snprintf(reason, sizeof(reason),
                      "FELL at t = %.3f s: the robot left the wall at x = %.3f m, y = %.3f m (%.3f m off the wall "
                      "plane, sliding at %.2f m/s)",
                      static_cast<double>(t_ns + dt_ns) * 1e-9, p[0], p[1], p[2], std::hypot(v[0], v[1]));
        fell_reason = reason;
        if (!scenario.end_on.fall) spdlog::warn("solo: {} (the run goes on: end_on.fall is false)", reason);
      }
    }
    if (scene_schedule.isDue(k)) {
      scene_node.applyRobotStates(robot_state.get(k, Lag::kOneStep));
      depth_image.write(kScene, k, t_ns, scene::depthImageToIdl(scene_node.renderDepth()));
    }
    if (sealing_schedule.isDue(k)) {
      leakage.write(kSealing, k, t_ns, sealing_node.step(depth_image.get(k, Lag::kOneStep)));
      if (scenario.end_on.seal_over_nothing && !sealing_node.noSurfaceWarned().empty() && !seal_failure) {
        // As the service: this step's leakage is written, then the run fails (after the row).
        seal_failure = "participant '" + std::string(kSealing) + "' failed at step " + std::to_string(k) + ": " +
                       sealing_node.sealOverNothingReason(t_ns);
      }
      if (picture_files && picture_schedule.due(t_ns)) {
        const auto pictures = sealing_node.pictures();  // empty until a valid depth image came: next step
        for (const auto& [kind, png] : pictures) {
          for (const auto& name : picture_files->filesFor(kind, t_ns)) writeFile(pictures_dir / name, png);
        }
        if (!pictures.empty()) picture_schedule.served(t_ns);
      }
    }
    {  // recorder: every topic it records, at the recorder's stamps (one-step lag, initial states before)
      recorder.update(chamber_state.getRecorded(k), adhesion.getRecorded(k), leakage.getRecorded(k),
                      robot_state.getRecorded(k), drive_state.getRecorded(k));
      std::fputs(recorder.row(t_ns).c_str(), trace.get());
    }
    result.steps = k + 1;
    if (seal_failure) {
      result.outcome = "failed";
      result.reason = *seal_failure;
      result.exit_code = kExitFailed;
      break;
    }
    if (fell_reason && scenario.end_on.fall) {
      // The earliest horizon the clock can freeze at: everyone finishes the fall's step.
      result.outcome = "fell";
      result.reason = *fell_reason;
      result.exit_code = kExitFell;
      break;
    }
  }
  std::fflush(trace.get());
  result.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  result.sim_s = static_cast<double>(result.steps) * static_cast<double>(dt_ns) * 1e-9;

  const std::string culprit = result.outcome == "fell"     ? std::string(kDrive)
                              : result.outcome == "failed" ? std::string(kSealing)
                                                           : std::string();
  nlohmann::json summary =
      recorder::runSummary(recorder, scenario.name, result.wall_s, result.outcome, result.reason, culprit,
                           result.exit_code);
  summary["wheels_over_nothing"] = wheels_over_nothing;  // as the launcher adds it from the drive's lines
  std::ofstream(fs::path(options.out_dir) / "summary.json") << summary.dump(2) << "\n";
  spdlog::info("solo: {} rows in {}, outcome {}, {}", result.steps, trace_path, result.outcome,
               realtimeText(result.sim_s, result.wall_s));
  return result;
}

}  // namespace climbsim::solo
