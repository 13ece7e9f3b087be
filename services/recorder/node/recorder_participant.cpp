#include "recorder_participant.hpp"

#include <spdlog/spdlog.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>

#include "climbsim/leave_after_results.hpp"
#include "climbsim/errors.hpp"
#include "climbsim/grid_record.hpp"
#include "climbsim/height_grid.hpp"
#include "climbsim/run_summary/run_summary.hpp"
#include "climbsim/topic_names.hpp"
#include "climbsim/run_id_env.hpp"
#include "node/recording_thread.hpp"
#include "node/run_recording.hpp"
#include "node/sealing_picture_files.hpp"
#include "robotPubSubTypes.h"
#include "scenePubSubTypes.h"
#include "sealingPubSubTypes.h"
#include "thermoPubSubTypes.h"

namespace climbsim::recorder {
namespace {

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
  if (!in || !out) throw ConfigError(target.string() + ": cannot copy the scenario " + scenario_file + " there");
  out << "# Copy of " << fs::absolute(scenario_file).lexically_normal().string()
      << " (relative paths are relative to its directory)\n"
      << in.rdbuf();
  if (!overrides.empty()) {
    out << "\n# read with:\n";
    for (const auto& o : overrides) out << "#   --set " << o << "\n";
  }
  if (!out) throw ConfigError(target.string() + ": cannot write");
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

/// trace.csv's rows: each reaches the file within kFlushPeriod of the next one (a flush per row
/// is a system call per step); the owner flushes the last ones when the run ends.
class TraceRows {
 public:
  explicit TraceRows(std::FILE* file) : file_(file) {}
  void append(const std::string& line) {
    std::fputs(line.c_str(), file_);
    const auto now = std::chrono::steady_clock::now();
    if (now - last_flush_ >= kFlushPeriod) {
      std::fflush(file_);
      last_flush_ = now;
    }
  }

 private:
  static constexpr auto kFlushPeriod = std::chrono::milliseconds(20);
  std::FILE* file_;
  std::chrono::steady_clock::time_point last_flush_ = std::chrono::steady_clock::now();
};

/// How the run ended, from the clock's Stop (none: failed): the launcher exits with the same code.
run_summary::RunEnd runEnd(const std::optional<climbsim::Stop>& stop, int code) {
  run_summary::RunEnd end{"failed", "", "", code == kExitOk ? kExitFailed : code};
  if (!stop) return end;
  end.reason = stop->reason().c_str();
  end.culprit = stop->culprit().c_str();
  switch (stop->kind()) {
    case STOP_COMPLETED: end.outcome = "completed"; end.exit_code = kExitOk; break;
    case STOP_REQUESTED: end.outcome = "stopped"; end.exit_code = kExitStopped; break;
    case STOP_FELL: end.outcome = "fell"; end.exit_code = kExitFell; break;
    case STOP_FAILED: default: end.outcome = "failed"; end.exit_code = kExitFailed; break;
  }
  return end;
}

}  // namespace

int runRecorderParticipant(const ParticipantOptions& options, const RunDirectory& dir, RecorderSetup& setup) {
  TraceRecorder& recorder = setup.trace;
  const RecordedInputs& which = setup.inputs;
  const std::string& out_dir = dir.out_dir;
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  if (!dir.scenario_file.empty()) keepScenarioCopy(dir.scenario_file, dir.overrides, out_dir);
  const std::string trace_path = out_dir + "/trace.csv";
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> trace(std::fopen(trace_path.c_str(), "w"), &std::fclose);
  if (!trace) throw ConfigError(trace_path + ": cannot write (--out " + out_dir + ")");
  std::string header;
  for (const auto& c : recorder.columns()) header += (header.empty() ? "" : ",") + c;
  std::fprintf(trace.get(), "%s\n", header.c_str());

  RecordingFiles files;
  files.scenario = dir.scenario_file.empty() ? "" : out_dir + "/scenario.yaml";
  files.robot = dir.robot_file;
  const char* compose = std::getenv(kEnvComposeFile);
  files.compose = compose != nullptr ? compose : "";
  files.runner = compose != nullptr ? "launcher" : "recorder";
  TraceRows rows(trace.get());
  // run.mcap is written on its own thread, off the thread that answers the clock (its jobs
  // write rows: it is declared after them, and ends first).
  std::optional<RecordingThread> recording;
  if (dir.mcap) {
    recording.emplace(
        std::make_unique<RunRecording>(out_dir + "/run.mcap", which, dir.depth_grids, files, &setup.geometry));
  }

  LockstepParticipant participant(options);
  auto* states = which.chamber ? &participant.recordedInput<ChamberStatePubSubType>(topic::kChamberState) : nullptr;
  auto* forces = which.adhesion ? &participant.recordedInput<AdhesionForcePubSubType>(topic::kAdhesionForce) : nullptr;
  auto* leakage = which.leakage ? &participant.recordedInput<LeakagePubSubType>(topic::kLeakage) : nullptr;
  auto* poses = which.robot ? &participant.recordedInput<RobotStatePubSubType>(topic::kRobotState) : nullptr;
  auto* drives = which.drive ? &participant.recordedInput<DriveStatePubSubType>(topic::kDriveState) : nullptr;
  auto* valve_commands =
      which.commands ? &participant.recordedInput<ValveCommandPubSubType>(topic::kValveCommand) : nullptr;
  auto* engine_commands =
      which.commands ? &participant.recordedInput<EngineCommandPubSubType>(topic::kEngineCommand) : nullptr;
  auto* drive_commands =
      which.commands ? &participant.recordedInput<DriveCommandPubSubType>(topic::kDriveCommand) : nullptr;
  auto* grids = dir.depth_grids ? &participant.recordedInput<DepthGridPubSubType>(topic::kDepthGrid) : nullptr;
  // Whole depth images do not fit a record batch's sample: read as the sealing reads them.
  auto* images = which.depth_images && recording ? &participant.input<DepthImagePubSubType>(topic::kDepthImage) : nullptr;
  std::optional<GridRecorder> grid_file;
  if (grids) grid_file.emplace(gridRecordPath(out_dir), 1);  // the scene decimates already
  auto keepGrids = [&] {
    if (!grids) return;
    for (auto& g : grids->takeArrived()) {
      if (g.height_m().size() != static_cast<std::size_t>(g.size()) * g.size()) {
        recorder.countDropped();
        continue;
      }
      const HeightGrid grid{static_cast<int>(g.size()), g.cell_m(), g.height_m()};
      grid_file->offer(g.t_ns(), heightGridJson(grid, g.step(), g.t_ns()).dump());
      if (recording) recording->post([g = std::move(g)](RunRecording& r) { r.depthGrid(g); });
    }
  };

  // Sealing pictures at the scenario's times, written as they arrive (never into the trace).
  std::optional<SealingPictureFiles> sealing_files;
  std::unique_ptr<Reader<SealingImagePubSubType>> sealing_pictures;
  const std::string pictures_dir = out_dir + "/pictures";
  if (!setup.picture_times.empty()) {
    std::filesystem::create_directories(pictures_dir, ec);
    sealing_files.emplace(setup.picture_times);
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
  const int code = participant.run([&](const StepContext& ctx) {
    if (!started) {
      started = std::chrono::steady_clock::now();
      if (recording && participant.runStartMessage()) {
        recording->post([start = *participant.runStartMessage()](RunRecording& r) { r.runStart(start); });
      }
    }
    auto step_states = states ? states->get(ctx) : std::vector<ChamberState>{};
    auto step_forces = forces ? forces->get(ctx) : std::vector<AdhesionForce>{};
    auto step_leakage = leakage ? leakage->get(ctx) : std::vector<Leakage>{};
    auto step_poses = poses ? poses->get(ctx) : std::vector<RobotState>{};
    auto step_drives = drives ? drives->get(ctx) : std::vector<DriveState>{};
    recorder.update(step_states, step_forces, step_leakage, step_poses, step_drives);
    std::string line = recorder.row(ctx.t_ns);
    if (line.empty()) {  // the trace ended at the fall (end_on.fall): the steps up to the horizon are not recorded
      takePictures();
      return;
    }
    if (recording) {
      recording->post([t_ns = ctx.t_ns, s = std::move(step_states), f = std::move(step_forces),
                       l = std::move(step_leakage), p = std::move(step_poses),
                       d = std::move(step_drives)](RunRecording& r) { r.update(t_ns, s, f, l, p, d); });
      if (images) recording->post([i = images->get(ctx)](RunRecording& r) { r.depthImages(i); });
      if (which.commands) {
        recording->post([v = valve_commands->get(ctx), e = engine_commands->get(ctx),
                         d = drive_commands->get(ctx)](RunRecording& r) { r.commands(v, e, d); });
      }
      // The row follows its samples: a row reaches trace.csv only once the chunks before it
      // are on the file, so a recorder killed mid-run leaves a run.mcap that reads up to at
      // most a chunk (kChunkPeriodNs) before the end of trace.csv.
      recording->post([&rows, line = std::move(line)](RunRecording&) { rows.append(line); });
    } else {
      rows.append(line);
    }
    last_t_ns = ctx.t_ns;
    takePictures();
    keepGrids();
  });
  // Every row is flushed when the run ends, also when another service (or the recording) failed.
  if (recording) {
    try {
      recording->drain();
    } catch (const std::exception& e) {
      spdlog::error("recorder: {}", e.what());  // thrown again below, once the summary is written
    }
  }
  std::fflush(trace.get());
  keepGrids();
  if (sealing_pictures) {
    // The sealing computes a requested time's picture at its first due step at or after it:
    // every time at least one depth period before the last step has one. Wait for those
    // that are still on their way (not for ever: a run without the sealing has none).
    const std::int64_t covered_ns = last_t_ns - setup.depth_period_ns;
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
  const run_summary::RunEnd end = runEnd(participant.stopMessage(), code);
  const nlohmann::json summary = run_summary::runSummary(recorder.summary(), setup.label, wall_s, end);
  run_summary::writeSummary(out_dir, summary);
  if (recording) {
    if (participant.stopMessage()) {
      recording->post([stop = *participant.stopMessage()](RunRecording& r) { r.stop(stop); });
    }
    recording->post([&summary](RunRecording& r) { r.finish(summary); });
    recording->drain();
  }
  spdlog::info("recorder: {} rows in {}, outcome {}", summary["steps"].get<std::uint64_t>(), trace_path, end.outcome);
  leaveAfterResults(participant.name().c_str(), code);
  return code;
}

}  // namespace climbsim::recorder
