#include "solo_run.hpp"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <future>
#include <memory>
#include <optional>

#include <spdlog/spdlog.h>

#include "climbsim/errors.hpp"
#include "climbsim/realtime_text.hpp"
#include "climbsim/run_summary/run_summary.hpp"
#include "climbsim/run_summary/summary_additions.hpp"
#include "climbsim/scenario_and_robot.hpp"
#include "climbsim/topic_names.hpp"
#include "climbsim/wall/scene_xml.hpp"
#include "clock/configure.hpp"
#include "controller/configure.hpp"
#include "controller/node/controller_node.hpp"
#include "drive/configure.hpp"
#include "drive/node/drive_node.hpp"
#include "drive/node/drive_translate.hpp"
#include "drive/node/fall_report.hpp"
#include "drive/node/wheels_over_scene.hpp"
#include "recorder/configure.hpp"
#include "recorder/node/run_recording.hpp"
#include "recorder/node/sealing_picture_files.hpp"
#include "climbsim/run_prep/run_scene.hpp"
#include "scene/configure.hpp"
#include "scene/node/scene_node.hpp"
#include "scene/node/scene_translate.hpp"
#include "sealing/configure.hpp"
#include "sealing/node/picture_schedule.hpp"
#include "sealing/node/sealing_node.hpp"
#include "solo_clock_messages.hpp"
#include "solo_participant.hpp"
#include "stamped_bus.hpp"
#include "thermo/configure.hpp"
#include "thermo/node/thermo_node.hpp"
#include "thermo/node/thermo_translate.hpp"

namespace climbsim::solo {
namespace {
namespace fs = std::filesystem;

/// The participant names of the default composition (deploy/compose.yaml; one replica each).
constexpr const char* kScene = "scene";
constexpr const char* kSealing = "sealing";
constexpr const char* kThermo = "thermo";
constexpr const char* kDrive = "drive";
constexpr const char* kController = "controller";

void writeFile(const fs::path& path, const std::vector<unsigned char>& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (!out) spdlog::warn("solo: cannot write {}", path.string());
}

/// The run directory as the launcher prepares it: the resolved scenario every service reads,
/// no trace or summary of an earlier run. Returns the scenario read back from it.
Scenario prepareRunDirectory(const SoloOptions& options) {
  fs::create_directories(options.out_dir);
  // Keys an override made meaningless (--set controller.type=none on a set-point): said once.
  for (const auto& note : loadScenario(options.scenario_file, options.overrides).ignored) spdlog::warn("{}", note);
  const std::string text =
      surface::runScenarioText(options.scenario_file, options.overrides, options.build_dir, options.out_dir);
  const std::string scenario_file = (fs::path(options.out_dir) / "scenario.yaml").string();
  for (const char* stale : {"trace.csv", "summary.json", "run.mcap"}) fs::remove(fs::path(options.out_dir) / stale);
  {
    std::ofstream out(scenario_file, std::ios::trunc);
    out << text;
    if (!out) throw ConfigError(scenario_file + ": cannot write (--out " + options.out_dir + ")");
  }
  Scenario scenario = loadScenario(scenario_file);
  if (scenario.controller.kind == Scenario::ControllerKind::kExternal) {
    throw ConfigError(options.scenario_file + ": controller.type = external: a solo run has no DDS, so no external "
                      "controller can join it; use `climbsim run` (or another controller type)");
  }
  return scenario;
}

}  // namespace

SoloResult runSolo(const SoloOptions& options) {
  const Scenario scenario = prepareRunDirectory(options);
  const ScenarioAndRobot run = scenarioAndRobot(scenario);

  // --- every service configured as its main() configures it (configure.hpp of each), with
  // the options deploy/compose.yaml gives it
  const clock::ClockTiming timing = clock::scenarioClockTiming(scenario);
  const std::int64_t dt_ns = timing.dt_ns;
  const std::uint64_t end_step = timing.end_step;
  scene::SceneOverrides scene_overrides;
  scene_overrides.outputs = "depth";  // compose.yaml: --outputs depth
  scene::SceneSetup scene_setup = scene::configureScene(run, scene_overrides, options.build_dir);
  // The reduced depth grids go to run.mcap alone: without it no frame is rendered whole for them
  // (the sealing's pixels are the same in a whole frame and a masked one).
  scene_setup.frames.depth_grids = options.mcap;
  const sealing::SealingSetup sealing_setup = sealing::configureSealing(run);
  thermo::ThermoSetup thermo_setup = thermo::configureThermo(run);
  // The scene file is read once: the drive's copy is made in the background while the scene's
  // renderer indexes its own (each service reads it itself when they are processes).
  const auto scene_read =
      std::make_shared<const scene::SceneDescription>(scene::loadSceneDescription(scene_setup.scene_file));
  drive::DriveOverrides drive_overrides;
  drive_overrides.scene_read = scene_read;
  const drive::DriveSetup drive_setup = drive::configureDrive(run, drive_overrides, options.build_dir);
  const controller::ControllerParams controller_params = controller::configureController(run);
  recorder::RecorderSetup recorder_setup = recorder::configureRecorder(run);

  // The drive service's check of the wheels against the scene (summary.json's
  // wheels_over_nothing), loaded while the models are, as the drive loads it while joining.
  std::future<std::optional<drive::WheelsOverScene>> wheel_check_loading = std::async(
      std::launch::async, [&] { return drive::wheelCheckOnScene(drive_setup.wheel_scene, drive_setup.params.wheels); });

  // --- the models behind their nodes, on the schedules of the default composition: scene
  // (depth period, offset 0), sealing (depth period, offset 1), everyone else every step
  // As climbsim-scene: the sealing's pixels but at the frames read whole (docs/design.md#what-the-scene-renders).
  scene::SceneNode scene_node(scene::runSceneOf(*scene_read, scene_setup), scene_setup.params, scene_setup.frames);
  const sealing::SealingModel sealing_model(sealing_setup.params, run.geometry, sealing_setup.camera, run.robot_file);
  sealing::SealingNode sealing_node(sealing_model, sealing_setup.shard);
  sealing::PictureSchedule picture_schedule(sealing_setup.picture_times);
  thermo::ThermoNode thermo_node(std::move(thermo_setup.params), std::move(thermo_setup.segment_names),
                                 std::move(thermo_setup.basic_leak_area_m2));
  drive::DriveNode drive_node(drive_setup.params, drive_setup.wall, drive_setup.start, drive_setup.downforce_n);
  drive_node.holdUntil(drive_setup.hold_until_ns);
  controller::ControllerNode controller_node(controller_params);
  const auto depth_period = static_cast<std::uint32_t>(scenario.depthPeriodSteps());
  const Schedule every_step{1, 0};
  SoloParticipant scene_participant(kScene, Schedule{depth_period, 0}, scene_node);
  SoloParticipant sealing_participant(kSealing, Schedule{depth_period, 1 % depth_period}, sealing_node);
  SoloParticipant thermo_participant(kThermo, every_step, thermo_node);
  SoloParticipant drive_participant(kDrive, every_step, drive_node);
  SoloParticipant controller_participant(kController, every_step, controller_node);

  recorder::TraceRecorder& recorder = recorder_setup.trace;
  std::optional<recorder::SealingPictureFiles> picture_files;
  const fs::path pictures_dir = fs::path(options.out_dir) / "pictures";
  if (!recorder_setup.picture_times.empty()) {
    fs::create_directories(pictures_dir);
    picture_files.emplace(recorder_setup.picture_times);
  }

  // --- the topics, with the producers the roster has
  StampedTopic<climbsim::RobotState> robot_state(topic::kRobotState);
  StampedTopic<climbsim::DriveState> drive_state(topic::kDriveState);
  StampedTopic<climbsim::DepthImage> depth_image(topic::kDepthImage);
  StampedTopic<climbsim::Leakage> leakage(topic::kLeakage);
  StampedTopic<climbsim::ChamberState> chamber_state(topic::kChamberState);
  StampedTopic<climbsim::AdhesionForce> adhesion(topic::kAdhesionForce);
  StampedTopic<climbsim::ValveCommand> valve_command(topic::kValveCommand);
  StampedTopic<climbsim::EngineCommand> engine_command(topic::kEngineCommand);
  StampedTopic<climbsim::DriveCommand> drive_command(topic::kDriveCommand);
  robot_state.addProducer(kDrive, drive_participant.schedule());
  drive_state.addProducer(kDrive, drive_participant.schedule());
  depth_image.addProducer(kScene, scene_participant.schedule());
  leakage.addProducer(kSealing, sealing_participant.schedule());
  chamber_state.addProducer(kThermo, thermo_participant.schedule());
  adhesion.addProducer(kThermo, thermo_participant.schedule());
  if (controller_node.commandsValves()) valve_command.addProducer(kController, controller_participant.schedule());
  if (controller_node.commandsEngines()) engine_command.addProducer(kController, controller_participant.schedule());
  drive_command.addProducer(kController, controller_participant.schedule());

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

  // run.mcap: the samples the recorder reads, as the recorder of a distributed run writes them.
  // The scene's reduced depth images, as the scene service gives them to a recorder that records
  // them (compose.yaml: the recorder's --depth-grids).
  std::optional<recorder::RunRecording> recording;
  if (options.mcap) {
    recording.emplace((fs::path(options.out_dir) / "run.mcap").string(), recorder_setup.inputs, true,
                      recorder::RecordingFiles{(fs::path(options.out_dir) / "scenario.yaml").string(), run.robot_file,
                                               "", "solo"},
                      &recorder_setup.geometry);
  }
  if (recording) recording->runStart(soloRunStart(dt_ns, end_step,
                                  {{kController, controller_participant.schedule()},
                                   {kDrive, drive_participant.schedule()},
                                   {"recorder", every_step},
                                   {kScene, scene_participant.schedule()},
                                   {kSealing, sealing_participant.schedule()},
                                   {kThermo, thermo_participant.schedule()}}));

  scene::DepthGridSchedule depth_grids;
  bool reduce_depth = options.mcap;

  std::optional<drive::WheelsOverScene> wheel_check = wheel_check_loading.get();
  std::vector<run_summary::WheelOverNothing> wheels_over_nothing;

  SoloResult result;
  result.outcome = "completed";
  result.reason = "end of run after " + std::to_string(end_step) + " steps";
  std::optional<std::string> fell_reason;
  std::optional<std::string> seal_failure;  ///< end_on.seal_over_nothing: the run fails
  const auto started = std::chrono::steady_clock::now();
  // Every input is read with a one-step lag, so the order of the participants inside a step
  // changes nothing; this is the order of the loop (docs/design.md#the-loop).
  for (std::uint64_t k = 0; k < end_step; ++k) {
    if (options.stop != nullptr && options.stop->load()) {
      result.outcome = "stopped";
      result.reason = k > 0 ? "stopped on request after step " + std::to_string(k - 1) : "stopped on request before step 0";
      result.exit_code = kExitStopped;
      break;
    }
    const std::int64_t t_ns = static_cast<std::int64_t>(k) * dt_ns;

    controller_participant.step(k, t_ns, dt_ns, [&](const controller::ControllerCommands& commands) {
      if (commands.valves) valve_command.write(kController, k, t_ns, *commands.valves);
      if (commands.engines) engine_command.write(kController, k, t_ns, *commands.engines);
      drive_command.write(kController, k, t_ns, commands.drive);
    }, chamber_state, adhesion);
    thermo_participant.step(k, t_ns, dt_ns, [&](const thermo::ThermoOutputs& outputs) {
      chamber_state.write(kThermo, k, t_ns, thermo::chamberStateToIdl(outputs));
      auto force = thermo::adhesionForceToIdl(outputs);
      force.downforce_setpoint_n(thermo_node.downforceSetpoint());
      adhesion.write(kThermo, k, t_ns, std::move(force));
    }, leakage, valve_command, engine_command);
    drive_participant.step(k, t_ns, dt_ns, [&](const drive::DriveOutputs& outputs) {
      robot_state.write(kDrive, k, t_ns, drive::robotStateToIdl(outputs));
      drive_state.write(kDrive, k, t_ns, drive::driveStateToIdl(outputs));
      if (wheel_check) {
        for (const std::size_t w : wheel_check->newlyOverNothing(outputs)) {
          // The drive service's line, read into summary.json as the launcher reads it.
          const std::string line = wheel_check->overNothingText(outputs, w, t_ns + dt_ns);
          spdlog::warn("solo: {}", line);
          if (const auto wheel = run_summary::wheelOverNothingIn(line)) wheels_over_nothing.push_back(*wheel);
        }
      }
      if (outputs.fell && !fell_reason) {
        fell_reason = drive::fellReason(outputs, t_ns + dt_ns);
        if (!drive_setup.end_on_fall) spdlog::warn("solo: {} (the run goes on: end_on.fall is false)", *fell_reason);
      }
    }, drive_command, adhesion);
    scene_participant.step(k, t_ns, dt_ns, [&](scene::DepthImage image) {
      std::optional<climbsim::DepthGrid> reduced;
      if (reduce_depth) {
        try {
          reduced = depth_grids.offer(image, t_ns);
        } catch (const std::invalid_argument& e) {  // as the scene service: no grids then
          spdlog::warn("solo: no depth grid for replays: {}", e.what());
          reduce_depth = false;
        }
      }
      depth_image.write(kScene, k, t_ns, scene::depthImageToIdl(std::move(image)));
      if (reduced) {
        reduced->source(kScene);
        reduced->step(k);
        reduced->t_ns(t_ns);
        if (recording) recording->depthGrid(*reduced);
      }
    }, robot_state);
    sealing_participant.step(k, t_ns, dt_ns, [&](climbsim::Leakage leak) {
      leakage.write(kSealing, k, t_ns, std::move(leak));
      if (sealing_setup.end_on_seal_over_nothing && !sealing_node.noSurfaceWarned().empty() && !seal_failure) {
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
    }, depth_image);
    {  // recorder: every topic it records, at the recorder's stamps (one-step lag, initial states before)
      const auto states = chamber_state.getRecorded(k);
      const auto forces = adhesion.getRecorded(k);
      const auto leaks = leakage.getRecorded(k);
      const auto poses = robot_state.getRecorded(k);
      const auto drives = drive_state.getRecorded(k);
      recorder.update(states, forces, leaks, poses, drives);
      if (recording) recording->update(t_ns, states, forces, leaks, poses, drives);
      // recording.depth_images: the images as the recorder's own input reads them (one-step lag).
      if (recording && recorder_setup.inputs.depth_images) recording->depthImages(depth_image.get(k, Lag::kOneStep));
      // recording.commands: the controller's commands, as the recorder's own inputs read them.
      if (recording && recorder_setup.inputs.commands) {
        recording->commands(valve_command.getRecorded(k), engine_command.getRecorded(k), drive_command.getRecorded(k));
      }
      std::fputs(recorder.row(t_ns).c_str(), trace.get());
    }
    result.steps = k + 1;
    if (seal_failure) {
      result.outcome = "failed";
      result.reason = *seal_failure;
      result.exit_code = kExitFailed;
      break;
    }
    if (fell_reason && drive_setup.end_on_fall) {
      // The earliest horizon the clock can freeze at: everyone finishes the fall's step. The
      // recorder's next row would hold the fall: the trace ends before it, and the summary's
      // fell_at_s is its time, as in a distributed run.
      recorder.update(chamber_state.getRecorded(k + 1), adhesion.getRecorded(k + 1), leakage.getRecorded(k + 1),
                      robot_state.getRecorded(k + 1), drive_state.getRecorded(k + 1));
      recorder.row(t_ns + dt_ns);
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
  nlohmann::json summary = run_summary::runSummary(recorder.summary(), recorder_setup.label, result.wall_s,
                                                   {result.outcome, result.reason, culprit, result.exit_code});
  // As the launcher adds it from the drive's lines.
  summary["wheels_over_nothing"] = run_summary::wheelsOverNothingJson(wheels_over_nothing);
  run_summary::writeSummary(options.out_dir, summary);
  if (recording) {
    recording->stop(soloStop(result.steps, dt_ns, result.outcome, culprit, result.reason));
    recording->finish(summary);
  }
  spdlog::info("solo: {} rows in {}, outcome {}, {}", result.steps, trace_path, result.outcome,
               realtimeText(result.sim_s, result.wall_s));
  return result;
}

}  // namespace climbsim::solo
