#include "sealing_step_timing.hpp"

#include <algorithm>
#include <ctime>
#include <utility>

#include "sealing_node.hpp"
#include "sealing_surfaces.hpp"
#include "sealing_translate.hpp"

namespace climbsim::sealing::bench {

std::vector<DepthGrid> descentFrames(const PixelGrid& grid, int frames, double x0_m, double advance_m,
                                     std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  DepthGrid wall = testing::flatWall(grid, 0.001f);
  testing::addRoughness(wall, rng, 0.002, 0.012, 0.0002);
  std::vector<DepthGrid> out;
  for (int f = 0; f < frames; ++f) {
    DepthGrid d = wall;
    testing::Crack crack;
    crack.x_m = x0_m + advance_m * f;
    crack.angle_rad = 1.5707963267948966;  // along R's y: across the direction of travel
    crack.bottom_width_m = 0.010;
    crack.depth_m = 0.040;
    testing::addCrack(d, crack);
    testing::clampToCamera(d);
    out.push_back(std::move(d));
  }
  return out;
}

namespace {

/// Bytes written between two steps of a cold measurement: 4 times the machine's L2 per core.
constexpr std::size_t kEvictBytes = std::size_t{16} << 20;

/// CPU time of the calling thread [s]: what the step costs, not the waits of a shared machine.
double threadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace

StepTiming timeSealingStep(const RobotDescription& robot, const RobotGeometry& geometry, int px, StripOutline outline,
                           int frames, int rounds, bool cold) {
  const PixelGrid grid{px, px, 0.80 / px};
  SealingParams params = sealingParamsFromRobot(robot, geometry);
  params.strip_outline = outline;
  const SealingModel model(params, geometry, grid, "bench");
  SealingNode node(model, ShardSpec{});
  // The crack from the robot's lower outer strip (x = -0.37 m) to its upper one.
  std::vector<climbsim::DepthImage> samples;
  for (const DepthGrid& d : descentFrames(grid, frames, -0.38, 0.76 / frames, 1)) {
    samples.push_back(depthImageToIdl(d, -0.05, 0.05));
  }
  StepTiming t;
  t.px = px;
  t.frames = frames;
  t.sealing_px = model.masks().sealingPixels().size();
  std::vector<double> step_ms, copy_ms;
  std::vector<unsigned char> evict(cold ? kEvictBytes : 0);
  double sink = 0.0;
  for (int round = 0; round <= rounds; ++round) {
    double step_s = 0.0, copy_s = 0.0;
    for (const climbsim::DepthImage& sample : samples) {
      if (cold) {
        // What the other services do between two depth frames: every cache line of the core's
        // caches replaced (and the TLB's entries).
        for (std::size_t i = 0; i < evict.size(); i += 64) evict[i] = static_cast<unsigned char>(evict[i] + 1);
      }
      const double t0 = threadCpuSeconds();
      std::vector<climbsim::DepthImage> step_input{sample};
      const double t1 = threadCpuSeconds();
      const climbsim::Leakage leak = node.step(std::move(step_input));
      const double t2 = threadCpuSeconds();
      sink += leak.segments().front().leak_area_m2();
      copy_s += t1 - t0;
      step_s += t2 - t1;
    }
    if (round == 0) continue;  // warm-up: buffers sized, caches filled
    step_ms.push_back(1e3 * step_s / frames);
    copy_ms.push_back(1e3 * copy_s / frames);
  }
  const auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  t.step_ms = median(step_ms);
  t.frame_copy_ms = median(copy_ms);
  if (sink < 0.0) t.step_ms = -t.step_ms;  // never: keeps the leakage from being optimised away
  return t;
}

}  // namespace climbsim::sealing::bench
