/// climbsim-bench-sealing: the sealing model's speed (docs/design.md#sealing-and-leakage).
///  - production adaptation vs the paper's loop (oracle) on the same cracked frames at
///    256x256 and 1024x1024: time per frame and their ratio (target >= 20), with a check
///    that both give the same doubles;
///  - frames/s of the whole model (adaptation, travel, leakage of all 18 segments) at 1024x1024;
///  - shard_speedup_2 and _4: frames/s of 2 and 4 shard processes (forked, one shard each,
///    the same 1024x1024 frames) over one process computing every segment, in the same round
///    (median of the rounds); whole_copies_2: 2 processes each computing every segment at once
///    over one, what this machine's shared caches and memory leave of 2 cores for this model;
///  - lockstep throughput at 1024x1024 with 1 and 2 climbsim-sealing shards as processes
///    (clock + climbsim-test-depth-feeder + shards): steps/s from the difference of a short
///    and a long run, so that start-up and discovery cancel.
///  - sealing_step_ms: one step of the sealing service (SealingNode::step: check the sample,
///    adapt, leakage of every segment, the Leakage sample) at 256 px on crack-descent-like frames
///    (target <= 0.2 ms), with the copy of the frame's sample as its reference, and the same
///    with sub-pixel strip shares (sealing_step_timing.hpp).
/// Prints `bench: sealing: ...` lines and writes JSON to --out.

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <iostream>
#include <sstream>
#include <thread>

#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "adaptation.hpp"
#include "climbsim/domain_lease.hpp"
#include "climbsim/process.hpp"
#include "climbsim/robot/robot_description.hpp"
#include "sealing_model.hpp"
#include "sealing_step_timing.hpp"
#include "sealing_surfaces.hpp"
#include "climbsim/shard_tiles/shard_partition.hpp"

#ifndef CLIMBSIM_DEFAULT_ROBOT_FILE
#error "CLIMBSIM_DEFAULT_ROBOT_FILE must name the default robot description"
#endif

namespace {

namespace fs = std::filesystem;
using namespace climbsim;
using namespace climbsim::sealing;
using SteadyClock = std::chrono::steady_clock;

double secondsSince(SteadyClock::time_point start) {
  return std::chrono::duration<double>(SteadyClock::now() - start).count();
}

/// The structured faces of docs/scene-files.md#wall-patches under the robot: rough concrete, two
/// long vertical-walled cracks (10..40 mm deep, 5..40 mm wide), a hole, and a step of 5..15 mm.
DepthGrid crackedFrame(const PixelGrid& grid, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  DepthGrid d = testing::flatWall(grid);
  testing::addRoughness(d, rng, 0.0005, 0.02, 0.0002);
  for (int k = 0; k < 2; ++k) {
    testing::Crack c;
    c.x_m = testing::uniform(rng, -0.2, 0.2);
    c.y_m = testing::uniform(rng, -0.2, 0.2);
    c.angle_rad = testing::uniform(rng, 0.0, 3.14159);
    c.bottom_width_m = testing::uniform(rng, 0.005, 0.04);
    c.depth_m = testing::uniform(rng, 0.01, 0.04);
    testing::addCrack(d, c);
  }
  testing::addHole(d, testing::uniform(rng, -0.3, 0.3), testing::uniform(rng, -0.3, 0.3), 0.03, 0.03);
  testing::addStep(d, testing::uniform(rng, -0.2, 0.2), testing::uniform(rng, -0.2, 0.2),
                   testing::uniform(rng, 0.0, 6.28), testing::uniform(rng, 0.005, 0.015));
  testing::clampToCamera(d);
  return d;
}

struct Comparison {
  int px = 0;
  int frames = 0;
  double oracle_ms = 0.0;
  double production_ms = 0.0;
  double mean_passes = 0.0;
  bool equal = true;
};

Comparison compare(const RobotDescription& robot, const RobotGeometry& geometry, int px, int frames) {
  const PixelGrid grid{px, px, 0.80 / px};
  const SealingModel model(sealingParamsFromRobot(robot, geometry), geometry, grid, "bench");
  const SealingAdapter adapter(model.masks(), model.neighbourhood());
  Comparison c;
  c.px = px;
  c.frames = frames;
  std::vector<double> production;
  for (int f = 0; f < frames; ++f) {
    const DepthGrid depth = crackedFrame(grid, 100 + f);
    int passes = 0;
    auto start = SteadyClock::now();
    const auto oracle = adaptNaive(model.masks(), model.neighbourhood(), depth.height_m, &passes);
    c.oracle_ms += 1e3 * secondsSince(start);
    start = SteadyClock::now();
    adapter.adapt(depth.height_m, production);
    c.production_ms += 1e3 * secondsSince(start);
    c.mean_passes += passes;
    c.equal = c.equal && oracle.size() == production.size() &&
              std::memcmp(oracle.data(), production.data(), oracle.size() * sizeof(double)) == 0;
  }
  c.oracle_ms /= frames;
  c.production_ms /= frames;
  c.mean_passes /= frames;
  return c;
}

double framesPerSecond(const RobotDescription& robot, const RobotGeometry& geometry, int px, int frames) {
  const PixelGrid grid{px, px, 0.80 / px};
  const SealingModel model(sealingParamsFromRobot(robot, geometry), geometry, grid, "bench");
  std::vector<DepthGrid> depths;
  for (int f = 0; f < 4; ++f) depths.push_back(crackedFrame(grid, 200 + f));
  std::vector<std::size_t> all(model.segmentCount());
  for (std::size_t s = 0; s < all.size(); ++s) all[s] = s;
  SealingResult result;
  model.compute(depths[0], all, result);  // warm the buffers
  const auto start = SteadyClock::now();
  for (int f = 0; f < frames; ++f) model.compute(depths[f % depths.size()], all, result);
  return frames / secondsSince(start);
}

/// CPU time of the calling process [s] (user + system).
double processCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// Runs `work(i)` in forked processes i = 0..processes-1, each after its `prepare(i)`, released
/// at once; returns the wall time until the last is done [s] and fills `cpu_s` with each one's
/// CPU time for `work` [s].
double forkedWallSeconds(std::size_t processes, const std::function<void(std::size_t)>& prepare,
                         const std::function<void(std::size_t)>& work, std::vector<double>& cpu_s) {
  int go[2];
  int ready[2];
  int result[2];
  if (pipe(go) != 0 || pipe(ready) != 0 || pipe(result) != 0) throw std::runtime_error("pipe failed");
  std::vector<pid_t> children;
  for (std::size_t i = 0; i < processes; ++i) {
    const pid_t pid = fork();
    if (pid < 0) throw std::runtime_error("fork failed");
    if (pid == 0) {
      prepare(i);
      char byte = 1;
      if (write(ready[1], &byte, 1) != 1 || read(go[0], &byte, 1) != 1) _exit(3);
      const double cpu0 = processCpuSeconds();
      work(i);
      const double cpu = processCpuSeconds() - cpu0;
      if (write(result[1], &cpu, sizeof cpu) != sizeof cpu) _exit(4);
      _exit(0);
    }
    children.push_back(pid);
  }
  for (std::size_t i = 0; i < processes; ++i) {
    char byte = 0;
    if (read(ready[0], &byte, 1) != 1) throw std::runtime_error("a forked process did not get ready");
  }
  const auto start = SteadyClock::now();
  const std::string release(processes, '\1');
  if (write(go[1], release.data(), release.size()) != static_cast<ssize_t>(release.size())) {
    throw std::runtime_error("could not release the forked processes");
  }
  for (const pid_t pid : children) {
    int status = 0;
    if (waitpid(pid, &status, 0) != pid || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
      throw std::runtime_error("a forked process failed");
    }
  }
  const double seconds = secondsSince(start);
  cpu_s.assign(processes, 0.0);
  for (auto& cpu : cpu_s) {
    if (read(result[0], &cpu, sizeof cpu) != sizeof cpu) throw std::runtime_error("a forked process sent no CPU time");
  }
  for (const int fd : {go[0], go[1], ready[0], ready[1], result[0], result[1]}) close(fd);
  return seconds;
}

/// The machine's own parallel ceiling for N processes: N x (wall time of one process running
/// a fixed arithmetic loop that touches no memory) / (wall time of N such processes at once).
/// On N idle cores of their own it is N; on shared, throttled or hyper-threaded virtual CPUs
/// it is less, and no split of the work can beat it.
double parallelCeiling(std::size_t processes, long iterations) {
  const auto idle = [](std::size_t) {};
  const auto spin = [iterations](std::size_t) {
    volatile double x = 1.0;
    for (long i = 0; i < iterations; ++i) x = x * 1.0000001 + 1e-9;
  };
  std::vector<double> cpu;
  const double one = forkedWallSeconds(1, idle, spin, cpu);
  const double many = forkedWallSeconds(processes, idle, spin, cpu);
  return static_cast<double>(processes) * one / many;
}

/// A forked process that computes the sealing of its segments on the shared frames, `frames`
/// at a time whenever it is told to, and answers with the CPU time it took [s]. It lives for the
/// whole measurement, so that its memory (regions, buffers) stays where it is between rounds.
class FrameWorker {
 public:
  FrameWorker(const SealingModel& model, const std::vector<DepthGrid>& depths, std::vector<std::size_t> segments) {
    int to_child[2];
    int from_child[2];
    if (pipe(to_child) != 0 || pipe(from_child) != 0) throw std::runtime_error("pipe failed");
    pid_ = fork();
    if (pid_ < 0) throw std::runtime_error("fork failed");
    if (pid_ == 0) {
      close(to_child[1]);
      close(from_child[0]);
      SealingResult result;
      model.compute(depths[0], segments, result);  // region built, buffers warm
      double ready = 0.0;
      if (write(from_child[1], &ready, sizeof ready) != sizeof ready) _exit(3);
      std::int32_t frames = 0;
      while (read(to_child[0], &frames, sizeof frames) == sizeof frames && frames > 0) {
        const double cpu0 = processCpuSeconds();
        for (std::int32_t f = 0; f < frames; ++f) model.compute(depths[static_cast<std::size_t>(f) % depths.size()], segments, result);
        const double cpu = processCpuSeconds() - cpu0;
        if (write(from_child[1], &cpu, sizeof cpu) != sizeof cpu) _exit(4);
      }
      _exit(0);
    }
    close(to_child[0]);
    close(from_child[1]);
    to_ = to_child[1];
    from_ = from_child[0];
    (void)answer();  // ready
  }
  FrameWorker(const FrameWorker&) = delete;
  FrameWorker& operator=(const FrameWorker&) = delete;
  ~FrameWorker() {
    // Told to stop (0 frames): the workers forked later hold copies of this pipe, so its
    // closing alone would not reach it.
    const std::int32_t stop = 0;
    if (write(to_, &stop, sizeof stop) != sizeof stop) kill(pid_, SIGKILL);
    close(to_);
    close(from_);
    int status = 0;
    waitpid(pid_, &status, 0);
  }
  void go(std::int32_t frames) const {
    if (write(to_, &frames, sizeof frames) != sizeof frames) throw std::runtime_error("a frame worker is gone");
  }
  /// CPU seconds of the last go [s].
  double answer() const {
    double cpu = 0.0;
    if (read(from_, &cpu, sizeof cpu) != sizeof cpu) throw std::runtime_error("a frame worker died");
    return cpu;
  }

 private:
  pid_t pid_ = -1;
  int to_ = -1;
  int from_ = -1;
};

/// Frame workers released together: one per shard of N, or N computing every segment.
struct WorkerGroup {
  std::string name;
  std::size_t frames_per_go_factor = 1;  ///< frames counted per worker per go: N for copies, 1 for shards
  std::vector<std::unique_ptr<FrameWorker>> workers;

  /// Releases every worker for `frames` frames at once: frames/s (frames_per_go_factor x
  /// frames over the wall time until the last is done) and the largest CPU time per frame [ms].
  std::pair<double, double> run(std::int32_t frames) const {
    const auto start = SteadyClock::now();
    for (const auto& w : workers) w->go(frames);
    double max_cpu = 0.0;
    for (const auto& w : workers) max_cpu = std::max(max_cpu, w->answer());
    const double seconds = secondsSince(start);
    return {static_cast<double>(frames_per_go_factor) * frames / seconds, 1e3 * max_cpu / frames};
  }
};

/// Wall time of one lockstep run of `steps` steps with `shards` sealing processes [s].
double lockstepRun(const fs::path& bin, const fs::path& logs, int px, int shards, int steps) {
  DomainLease lease(200, 250);
  const std::string domain = std::to_string(lease.id());
  const std::string tag = std::to_string(shards) + "shards-" + std::to_string(steps) + "steps";
  std::string roster = "feeder";
  for (int i = 0; i < shards; ++i) roster += ",sealing" + std::to_string(i);
  std::vector<ChildProcess> children;
  auto start = [&](const std::string& name, std::vector<std::string> argv) {
    ProcessSpec spec;
    spec.argv = std::move(argv);
    spec.argv.insert(spec.argv.end(), {"--domain", domain});
    spec.output_file = (logs / (tag + "-" + name + ".log")).string();
    fs::remove(spec.output_file);
    children.emplace_back(spec);
  };
  const auto begin = SteadyClock::now();
  start("clock", {(bin / "climbsim-clock").string(), "--roster", roster, "--steps", std::to_string(steps),
                  "--step-ms", "5"});
  start("feeder", {(bin / "climbsim-test-depth-feeder").string(), "--name", "feeder", "--camera-px",
                   std::to_string(px), "--distinct", "4"});
  for (int i = 0; i < shards; ++i) {
    start("sealing" + std::to_string(i), {(bin / "climbsim-sealing").string(), "--name", "sealing" + std::to_string(i),
                                          "--shard", std::to_string(i) + "/" + std::to_string(shards),
                                          "--camera-px", std::to_string(px)});
  }
  for (auto& child : children) {
    const auto code = child.waitFor(std::chrono::minutes(5));
    if (!code || *code != 0) {
      throw std::runtime_error("lockstep run " + tag + " failed (exit " + (code ? std::to_string(*code) : "none") +
                               "); logs in " + logs.string());
    }
  }
  return secondsSince(begin);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"climbsim-bench-sealing: sealing adaptation and service throughput"};
  std::string out_file;
  std::string robot_file = CLIMBSIM_DEFAULT_ROBOT_FILE;
  fs::path bin_dir = fs::canonical("/proc/self/exe").parent_path();
  int steps = 100;
  int shard_frames = 150;
  int shard_rounds = 15;
  bool skip_lockstep = false;
  bool step_only = false;
  int step_frames = 200;
  int step_rounds = 9;
  app.add_option("--out", out_file, "JSON result file")->required();
  app.add_option("--robot", robot_file, "robot description");
  app.add_option("--bin-dir", bin_dir, "where climbsim-clock, -sealing and -test-depth-feeder are");
  app.add_option("--steps", steps, "extra lockstep steps of the long run over the short one");
  app.add_option("--shard-frames", shard_frames, "frames each worker process computes per round for shard_speedup_N")
      ->check(CLI::Range(1, 100000));
  app.add_option("--shard-rounds", shard_rounds, "rounds of 1, 2, 4 shard processes and 2 whole copies (medians)")
      ->check(CLI::Range(1, 99));
  app.add_flag("--no-lockstep", skip_lockstep, "model measurements only");
  app.add_flag("--step-only", step_only, "only sealing_step_ms (the service's step at 256 px)");
  app.add_option("--step-frames", step_frames, "crack-descent-like frames per round of sealing_step_ms")
      ->check(CLI::Range(1, 100000));
  app.add_option("--step-rounds", step_rounds, "rounds of sealing_step_ms (median)")->check(CLI::Range(1, 999));
  CLI11_PARSE(app, argc, argv);
  // A frame worker that died makes its pipe's write fail (and is named), not kill the bench.
  std::signal(SIGPIPE, SIG_IGN);
  try {
    const RobotDescription robot = loadRobotDescription(robot_file);
    const RobotGeometry geometry = computeGeometry(robot);
    nlohmann::ordered_json json;
    {
      constexpr double kStepTarget_ms = 0.2;
      const bench::StepTiming whole =
          bench::timeSealingStep(robot, geometry, 256, StripOutline::kPixelCentres, step_frames, step_rounds, true);
      const bench::StepTiming hot =
          bench::timeSealingStep(robot, geometry, 256, StripOutline::kPixelCentres, step_frames, step_rounds, false);
      const bench::StepTiming shares =
          bench::timeSealingStep(robot, geometry, 256, StripOutline::kSubpixelShares, step_frames, step_rounds, true);
      std::printf("bench: sealing: sealing_step_ms=%.3f (CPU ms of SealingNode::step per depth frame, px=256, %d "
                  "crack-descent-like frames x %d rounds, median; caches replaced between steps as in a run; %zu "
                  "sealing px) target=%.1f met=%s frame_copy_ms=%.3f (copying the frame's sample that the step takes: "
                  "step / copy %.1f) hot_step_ms=%.3f (steps back to back, caches warm) subpixel_step_ms=%.3f (the "
                  "same as sealing_step_ms with depth_camera.subpixel; %zu sealing px)\n",
                  whole.step_ms, step_frames, step_rounds, whole.sealing_px, kStepTarget_ms,
                  whole.step_ms <= kStepTarget_ms ? "yes" : "no", whole.frame_copy_ms, whole.step_ms / whole.frame_copy_ms,
                  hot.step_ms, shares.step_ms, shares.sealing_px);
      std::fflush(stdout);
      double load[1] = {0.0};
      if (getloadavg(load, 1) == 1) json["loadavg"] = load[0];  // of this shared machine, while measuring
      json["sealing_step_ms"] = whole.step_ms;
      json["sealing_step_target_ms"] = kStepTarget_ms;
      json["frame_copy_ms"] = whole.frame_copy_ms;
      json["hot_step_ms"] = hot.step_ms;
      json["subpixel_step_ms"] = shares.step_ms;
      if (step_only) {
        std::ofstream(out_file) << json.dump(2) << '\n';
        return 0;
      }
    }
    json["comparisons"] = nlohmann::ordered_json::array();
    for (const auto& [px, frames] : {std::pair{256, 20}, std::pair{1024, 3}}) {
      const Comparison c = compare(robot, geometry, px, frames);
      const double ratio = c.oracle_ms / c.production_ms;
      std::printf("bench: sealing: adaptation px=%d frames=%d oracle_ms=%.3f production_ms=%.3f ratio=%.1f "
                  "oracle_passes=%.1f equal=%s\n",
                  c.px, c.frames, c.oracle_ms, c.production_ms, ratio, c.mean_passes, c.equal ? "true" : "false");
      json["comparisons"].push_back({{"px", c.px}, {"frames", c.frames}, {"oracle_ms", c.oracle_ms},
                                     {"production_ms", c.production_ms}, {"ratio", ratio},
                                     {"oracle_passes", c.mean_passes}, {"equal", c.equal}});
      if (!c.equal) throw std::runtime_error("production and oracle differ at " + std::to_string(px) + " px");
    }
    const double fps_256 = framesPerSecond(robot, geometry, 256, 400);
    std::printf("bench: sealing: model px=256 frames_per_s=%.1f ms_per_frame=%.3f\n", fps_256, 1e3 / fps_256);
    json["model_frames_per_s_256"] = fps_256;
    const double fps = framesPerSecond(robot, geometry, 1024, 50);
    std::printf("bench: sealing: model px=1024 frames_per_s=%.1f\n", fps);
    json["model_frames_per_s_1024"] = fps;
    std::fflush(stdout);

    // Shards as processes on the same frames (target: shard_speedup_2 >= 1.7 on 2 cores).
    const std::size_t whole_px = SealingModel(sealingParamsFromRobot(robot, geometry), geometry,
                                              PixelGrid{1024, 1024, 0.80 / 1024}, "bench")
                                     .masks()
                                     .sealingPixels()
                                     .size();
    // Persistent workers (FrameWorker): one process computing every segment; 2 and 4 shard
    // processes; 2 processes each computing every segment. In every round each group computes
    // the same frames, in an order that rotates from round to round, back to back, so that a
    // slow spell of this shared machine weighs on a round's groups alike; the ratios are taken
    // within a round and their medians reported.
    const PixelGrid shard_grid{1024, 1024, 0.80 / 1024};
    const SealingModel shard_model(sealingParamsFromRobot(robot, geometry), geometry, shard_grid, "bench");
    std::vector<DepthGrid> shard_depths;
    for (int f = 0; f < 4; ++f) {
      shard_depths.push_back(crackedFrame(shard_grid, 300 + f));
      // As the service does: the image's highest pixel bounds the shards' regions.
      shard_depths.back().upper_bound_m =
          *std::max_element(shard_depths.back().height_m.begin(), shard_depths.back().height_m.end());
    }
    std::vector<std::size_t> every_segment(shard_model.segmentCount());
    for (std::size_t s = 0; s < every_segment.size(); ++s) every_segment[s] = s;
    std::map<std::size_t, double> adapted;
    std::vector<WorkerGroup> groups;
    for (const std::size_t n : {1u, 2u, 4u}) {
      WorkerGroup group;
      group.name = std::to_string(n);
      const auto parts = n == 1 ? std::vector<std::vector<std::size_t>>{every_segment}
                                : partitionSegments(shard_model.masks(), n);
      adapted[n] = 0.0;
      for (const auto& part : parts) {
        SealingResult r;
        for (const auto& depth : shard_depths) {
          shard_model.compute(depth, part, r);
          adapted[n] += static_cast<double>(r.adapted_px) / shard_depths.size();
        }
        group.workers.push_back(std::make_unique<FrameWorker>(shard_model, shard_depths, part));
      }
      groups.push_back(std::move(group));
    }
    {
      WorkerGroup copies;
      copies.name = "copies";
      copies.frames_per_go_factor = 2;
      for (int i = 0; i < 2; ++i) copies.workers.push_back(std::make_unique<FrameWorker>(shard_model, shard_depths, every_segment));
      groups.push_back(std::move(copies));
    }
    std::map<std::string, std::vector<double>> group_fps;
    std::map<std::string, std::vector<double>> group_cpu_ms;
    std::map<std::size_t, std::vector<double>> ceiling;
    for (const std::size_t n : {2u, 4u}) ceiling[n].push_back(parallelCeiling(n, 200'000'000));
    for (int round = 0; round < shard_rounds; ++round) {
      for (std::size_t g = 0; g < groups.size(); ++g) {
        const WorkerGroup& group = groups[(g + static_cast<std::size_t>(round)) % groups.size()];
        const auto [fps, cpu_ms] = group.run(shard_frames);
        group_fps[group.name].push_back(fps);
        group_cpu_ms[group.name].push_back(cpu_ms);
      }
    }
    for (const std::size_t n : {2u, 4u}) ceiling[n].push_back(parallelCeiling(n, 200'000'000));
    groups.clear();
    std::map<std::size_t, std::vector<double>> shard_fps{{1, group_fps["1"]}, {2, group_fps["2"]}, {4, group_fps["4"]}};
    std::map<std::size_t, std::vector<double>> shard_cpu_ms{
        {1, group_cpu_ms["1"]}, {2, group_cpu_ms["2"]}, {4, group_cpu_ms["4"]}};
    const std::vector<double> whole_copies_fps = group_fps["copies"];
    const auto median = [](std::vector<double> v) {
      std::sort(v.begin(), v.end());
      return v[v.size() / 2];
    };
    const double fps_1 = median(shard_fps[1]);
    const double cpu_1 = median(shard_cpu_ms[1]);
    std::printf("bench: sealing: shards px=1024 frames=%d rounds=%d shards=1 frames_per_s=%.1f cpu_ms_per_frame=%.2f "
                "adapted_px=%.0f\n",
                shard_frames, shard_rounds, fps_1, cpu_1, adapted[1]);
    json["shards"] = nlohmann::ordered_json::array();
    json["shards"].push_back(
        {{"shards", 1}, {"frames_per_s", fps_1}, {"cpu_ms_per_frame", cpu_1}, {"adapted_px", adapted[1]}});
    for (const std::size_t n : {2u, 4u}) {
      const double fps_n = median(shard_fps[n]);
      // Each round's N processes over the same round's one process (measured back to back, so
      // that a slow spell of this shared machine weighs on both), the median of the rounds.
      std::vector<double> round_ratios;
      for (std::size_t r = 0; r < shard_fps[n].size(); ++r) round_ratios.push_back(shard_fps[n][r] / shard_fps[1][r]);
      const double speedup = median(round_ratios);
      const std::string rounds_text = fmt::format("{:.2f}", fmt::join(round_ratios, ", "));
      const double cpu_n = median(shard_cpu_ms[n]);
      const double cpu_split = cpu_1 / cpu_n;
      const double ceiling_n = 0.5 * (ceiling[n].front() + ceiling[n].back());  // before and after the rounds
      std::printf("bench: sealing: shard_speedup_%zu=%.2f (median of the rounds' frames_per_s with %zu shard processes / "
                  "with one in the same round: %s; medians %.1f / %.1f; cores=%u) cpu_split_%zu=%.2f (CPU ms per frame "
                  "of one process %.2f / of the busiest of %zu shards %.2f) parallel_ceiling_%zu=%.2f (%zu x wall of 1 "
                  "spinning process / wall of %zu at once, mean of before and after) adapted_px_over_whole=%.3f (%.0f / %zu)\n",
                  n, speedup, n, rounds_text.c_str(), fps_n, fps_1, std::thread::hardware_concurrency(), n, cpu_split,
                  cpu_1, n, cpu_n, n, ceiling_n, n, n, adapted[n] / whole_px, adapted[n], whole_px);
      json["shard_speedup_" + std::to_string(n)] = speedup;
      json["shard_speedup_" + std::to_string(n) + "_rounds"] = round_ratios;
      json["cpu_split_" + std::to_string(n)] = cpu_split;
      json["parallel_ceiling_" + std::to_string(n)] = ceiling_n;
      json["shards"].push_back({{"shards", n},
                                {"frames_per_s", fps_n},
                                {"cpu_ms_per_frame", cpu_n},
                                {"adapted_px", adapted[n]}});
    }
    {
      // The same model unsplit in two processes at once: the most two processes of it get here
      // (shared caches and memory), the ceiling that shard_speedup_2 is to be read against.
      std::vector<double> ratios;
      for (std::size_t r = 0; r < whole_copies_fps.size(); ++r) ratios.push_back(whole_copies_fps[r] / shard_fps[1][r]);
      const double copies = median(ratios);
      std::printf("bench: sealing: whole_copies_2=%.2f (median of the rounds' frames_per_s of 2 processes each computing "
                  "every segment at once / of one, same round) split_efficiency_2=%.2f (shard_speedup_2 / "
                  "whole_copies_2)\n",
                  copies, json["shard_speedup_2"].get<double>() / copies);
      json["whole_copies_2"] = copies;
      json["split_efficiency_2"] = json["shard_speedup_2"].get<double>() / copies;
    }
    std::fflush(stdout);

    if (!skip_lockstep) {
      const fs::path logs = fs::path(out_file).parent_path() / "sealing-logs";
      fs::create_directories(logs);
      json["lockstep"] = nlohmann::ordered_json::array();
      double one_shard = 0.0;
      for (const int shards : {1, 2}) {
        const int short_steps = 20;
        const double t_short = lockstepRun(bin_dir, logs, 1024, shards, short_steps);
        const double t_long = lockstepRun(bin_dir, logs, 1024, shards, short_steps + steps);
        const double steps_per_s = steps / (t_long - t_short);
        if (shards == 1) one_shard = steps_per_s;
        std::printf("bench: sealing: lockstep px=1024 shards=%d steps_per_s=%.1f vs_1_shard=%.2f\n", shards,
                    steps_per_s, steps_per_s / one_shard);
        std::fflush(stdout);
        json["lockstep"].push_back(
            {{"px", 1024}, {"shards", shards}, {"steps_per_s", steps_per_s}, {"vs_1_shard", steps_per_s / one_shard}});
      }
    }
    std::ofstream(out_file) << json.dump(2) << '\n';
  } catch (const std::exception& e) {
    std::cerr << "climbsim-bench-sealing: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
