/// climbsim-recorder: a roster member (so the trace is complete) that writes trace.csv (one row
/// per step, docs/scenario-files.md) and summary.json into --out. Its inputs come in record batches
/// (one delivery per producer per acknowledgement, not per topic per step: RecordedInput). Rows are
/// flushed within 20 ms and at the end: a run that ends early keeps every row computed so far.
/// With --scenario the robot and the label come from the scenario file, and the run directory
/// keeps a copy of it as scenario.yaml; the sealing pictures of its pictures.sealing_at_s
/// (sealing/SealingPicture, published by climbsim-sealing) are written as
/// pictures/sealing_<kind>_<t>s.png. Pictures change nothing in trace.csv. With --depth-grids
/// it records scene/DepthGrid (the scene's reduced depth image every 0.1 s, in its record
/// batches) into viewer/depth_grids.jsonl: the wall of `climbsim view RUN_DIR`.

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "climbsim/errors.hpp"
#include "climbsim/grid_record.hpp"
#include "climbsim/height_grid.hpp"
#include "climbsim/lockstep_participant.hpp"
#include "climbsim/logging.hpp"
#include "climbsim/main_guard.hpp"
#include "climbsim/names.hpp"
#include "climbsim/robot/robot_description.hpp"
#include "climbsim/robot/robot_geometry.hpp"
#include "climbsim/scenario.hpp"
#include "climbsim/topic_names.hpp"
#include "node/run_summary.hpp"
#include "node/sealing_picture_files.hpp"
#include "node/trace_recorder.hpp"
#include "robotPubSubTypes.h"
#include "scenePubSubTypes.h"
#include "sealingPubSubTypes.h"
#include "thermoPubSubTypes.h"

#ifndef CLIMBSIM_DEFAULT_ROBOT_FILE
#error "CLIMBSIM_DEFAULT_ROBOT_FILE must name the default robot description"
#endif

namespace {

struct RecordedInputs {
  bool chamber = true, adhesion = true, leakage = true, robot = true, drive = true;
};

RecordedInputs parseInputs(const std::string& list) {
  const auto chosen = climbsim::parseChoiceList("--inputs", list, {"chamber", "adhesion", "leakage", "robot", "drive"});
  return RecordedInputs{chosen.count("chamber") != 0, chosen.count("adhesion") != 0, chosen.count("leakage") != 0,
                        chosen.count("robot") != 0, chosen.count("drive") != 0};
}

/// Copies the scenario into out_dir/scenario.yaml unless it is that file (the launcher's
/// resolved copy). A header names the original, against whose directory relative robot and
/// scene paths are meant; the --set overrides it was read with are noted at the end.
void keepScenarioCopy(const std::string& scenario_file, const std::vector<std::string>& overrides,
                      const std::string& out_dir) {
  namespace fs = std::filesystem;
  const fs::path target = fs::path(out_dir) / "scenario.yaml";
  std::error_code ec;
  if (fs::equivalent(scenario_file, target, ec)) return;
  std::ifstream in(scenario_file);
  std::ofstream out(target, std::ios::trunc);
  if (!in || !out) throw climbsim::ConfigError(target.string() + ": cannot copy the scenario " + scenario_file + " there");
  out << "# Copy of " << fs::absolute(scenario_file).lexically_normal().string()
      << " (relative paths are relative to its directory)\n"
      << in.rdbuf();
  if (!overrides.empty()) {
    out << "\n# read with:\n";
    for (const auto& o : overrides) out << "#   --set " << o << "\n";
  }
  if (!out) throw climbsim::ConfigError(target.string() + ": cannot write");
}

/// Writes `png` to each of `files` in `dir`; a failure is logged (pictures never fail the run).
void writePictureFiles(const std::string& dir, const std::vector<std::string>& files,
                       const std::vector<unsigned char>& png) {
  for (const auto& name : files) {
    const std::string path = dir + "/" + name;
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
    if (!out) spdlog::warn("recorder: cannot write {}", path);
  }
}

}  // namespace

int main(int argc, char** argv) {
  using namespace climbsim;
  CLI::App app{"climbsim-recorder: writes trace.csv and summary.json of a run"};
  ParticipantOptions options;
  std::string out_dir;
  std::string robot_file = CLIMBSIM_DEFAULT_ROBOT_FILE;
  std::string inputs_list = "chamber,adhesion,leakage,robot,drive";
  std::string label;
  std::string scenario_file;
  std::vector<std::string> overrides;
  bool depth_grids = false;
  options.addOptions(app);
  app.add_option("--out", out_dir, "run directory to write trace.csv and summary.json into")->required();
  auto* scenario_opt = app.add_option(
      "--scenario", scenario_file,
      "scenario file (deploy/scenarios/*.yaml): the robot and the default --label (its name) come from it, and "
      "it is copied into --out as scenario.yaml; excludes --robot");
  app.add_option("--set", overrides, "override a scenario key (repeatable)")->needs(scenario_opt);
  app.add_option("--robot", robot_file, "robot description (segment and wheel columns)")->excludes(scenario_opt);
  app.add_option("--inputs", inputs_list, "topics to record: chamber,adhesion,leakage,robot,drive or none");
  app.add_flag("--depth-grids", depth_grids,
               "record scene/DepthGrid into viewer/depth_grids.jsonl (needs a scene writing depth on the roster)");
  app.add_option("--label", label, "scenario name written into summary.json (default: the scenario's name)");
  return guardedMain(app, argc, argv, "recorder", [&]() -> int {
    initLogging(options.name);
    const RecordedInputs which = parseInputs(inputs_list);
    std::optional<Scenario> scenario;
    if (!scenario_file.empty()) {
      scenario = loadScenario(scenario_file, overrides);
      robot_file = scenario->robotPath();
      if (app.count("--label") == 0) label = scenario->name;
    }
    const RobotDescription robot = loadRobotDescription(robot_file);
    const RobotGeometry geometry = computeGeometry(robot);
    recorder::TraceRecorder recorder(segmentNames(geometry), basicLeakAreas(robot, geometry),
                                     static_cast<int>(geometry.wheels.size()));
    if (scenario) {
      recorder.setSlideLimit(scenario->slide_limit_m);
      recorder.setDownforceFrom(std::llround(scenario->start.hold_s * 1e9));
    }
    std::error_code ec;
    std::filesystem::create_directories(out_dir, ec);
    if (scenario) keepScenarioCopy(scenario_file, overrides, out_dir);
    const std::string trace_path = out_dir + "/trace.csv";
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> trace(std::fopen(trace_path.c_str(), "w"), &std::fclose);
    if (!trace) throw ConfigError(trace_path + ": cannot write (--out " + out_dir + ")");
    std::string header;
    for (const auto& c : recorder.columns()) header += (header.empty() ? "" : ",") + c;
    std::fprintf(trace.get(), "%s\n", header.c_str());

    LockstepParticipant participant(options);
    auto* states = which.chamber ? &participant.recordedInput<ChamberStatePubSubType>(topic::kChamberState) : nullptr;
    auto* forces = which.adhesion ? &participant.recordedInput<AdhesionForcePubSubType>(topic::kAdhesionForce) : nullptr;
    auto* leakage = which.leakage ? &participant.recordedInput<LeakagePubSubType>(topic::kLeakage) : nullptr;
    auto* poses = which.robot ? &participant.recordedInput<RobotStatePubSubType>(topic::kRobotState) : nullptr;
    auto* drives = which.drive ? &participant.recordedInput<DriveStatePubSubType>(topic::kDriveState) : nullptr;
    auto* grids = depth_grids ? &participant.recordedInput<DepthGridPubSubType>(topic::kDepthGrid) : nullptr;
    std::optional<GridRecorder> grid_file;
    if (grids) grid_file.emplace(gridRecordPath(out_dir), 1);  // the scene decimates already
    auto keepGrids = [&] {
      if (!grids) return;
      for (const auto& g : grids->takeArrived()) {
        if (g.height_m().size() != static_cast<std::size_t>(g.size()) * g.size()) {
          recorder.countDropped();
          continue;
        }
        const HeightGrid grid{static_cast<int>(g.size()), g.cell_m(), g.height_m()};
        grid_file->offer(g.t_ns(), heightGridJson(grid, g.step(), g.t_ns()).dump());
      }
    };

    // Sealing pictures at the scenario's times, written as they arrive (never into the trace).
    std::optional<recorder::SealingPictureFiles> sealing_files;
    std::unique_ptr<Reader<SealingImagePubSubType>> sealing_pictures;
    const std::string pictures_dir = out_dir + "/pictures";
    if (scenario && !scenario->pictures.sealing_at_s.empty()) {
      std::filesystem::create_directories(pictures_dir, ec);
      sealing_files.emplace(scenario->pictures.sealing_at_s);
      sealing_pictures = std::make_unique<Reader<SealingImagePubSubType>>(participant.dds(), topic::kSealingPicture,
                                                                          qos::kPictures, participant.notifier());
    }
    auto takePictures = [&]() -> bool {
      if (!sealing_pictures) return false;
      const auto received = sealing_pictures->take();
      for (const auto& r : received) {
        writePictureFiles(pictures_dir, sealing_files->filesFor(r.data.kind().to_string(), r.data.t_ns()), r.data.png());
      }
      return !received.empty();
    };
    std::int64_t last_t_ns = 0;

    std::optional<std::chrono::steady_clock::time_point> started;
    constexpr auto kFlushPeriod = std::chrono::milliseconds(20);
    auto last_flush = std::chrono::steady_clock::now();
    const int code = participant.run([&](const StepContext& ctx) {
      if (!started) started = std::chrono::steady_clock::now();
      recorder.update(states ? states->get(ctx) : std::vector<ChamberState>{},
                      forces ? forces->get(ctx) : std::vector<AdhesionForce>{},
                      leakage ? leakage->get(ctx) : std::vector<Leakage>{},
                      poses ? poses->get(ctx) : std::vector<RobotState>{},
                      drives ? drives->get(ctx) : std::vector<DriveState>{});
      const std::string line = recorder.row(ctx.t_ns);
      std::fputs(line.c_str(), trace.get());
      // Rows reach the file within kFlushPeriod (a flush per row is a system call per step);
      // every row is flushed when the run ends, also when another service failed.
      const auto now = std::chrono::steady_clock::now();
      if (now - last_flush >= kFlushPeriod) {
        std::fflush(trace.get());
        last_flush = now;
      }
      last_t_ns = ctx.t_ns;
      takePictures();
      keepGrids();
    });
    std::fflush(trace.get());
    keepGrids();
    if (sealing_pictures) {
      // The sealing computes a requested time's picture at its first due step at or after it:
      // every time at least one depth period before the last step has one. Wait for those
      // that are still on their way (not for ever: a run without the sealing has none).
      const std::int64_t period_ns = scenario->depthPeriodSteps() * scenario->step_ns;
      const std::int64_t covered_ns = last_t_ns - period_ns;
      const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
      while (sealing_files->missingUpTo(covered_ns) > 0) {
        const auto seen = participant.notifier().generation();
        if (takePictures()) continue;
        if (sealing_pictures->matchedWriters() == 0) break;
        if (!participant.notifier().waitChanged(seen, deadline)) break;
      }
      takePictures();
      if (const std::size_t missing = sealing_files->missingUpTo(covered_ns); missing > 0) {
        spdlog::warn("recorder: {} sealing pictures did not arrive", missing);
      }
      spdlog::info("recorder: {} sealing pictures in {}", sealing_files->written(), pictures_dir);
    }
    const double wall_s =
        started ? std::chrono::duration<double>(std::chrono::steady_clock::now() - *started).count() : 0.0;
    // How the run ended, from the clock's Stop: the launcher exits with the same code.
    std::string outcome = "failed", reason, culprit;
    int run_code = code == kExitOk ? kExitFailed : code;
    if (const auto& stop = participant.stopMessage()) {
      reason = stop->reason().c_str();
      culprit = stop->culprit().c_str();
      switch (stop->kind()) {
        case STOP_COMPLETED: outcome = "completed"; run_code = kExitOk; break;
        case STOP_REQUESTED: outcome = "stopped"; run_code = kExitStopped; break;
        case STOP_FELL: outcome = "fell"; run_code = kExitFell; break;
        case STOP_FAILED: default: outcome = "failed"; run_code = kExitFailed; break;
      }
    }
    const nlohmann::json summary = recorder::runSummary(recorder, label, wall_s, outcome, reason, culprit, run_code);
    std::ofstream(out_dir + "/summary.json") << summary.dump(2) << "\n";
    spdlog::info("recorder: {} rows in {}, outcome {}", summary["steps"].get<std::uint64_t>(), trace_path, outcome);
    return code;
  });
}
