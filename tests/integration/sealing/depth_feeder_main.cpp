/// climbsim-test-depth-feeder: feeds climbsim-sealing in the integration tests and the
/// benchmark. Each due step k it writes a synthetic scene/DepthImage (randomSurface of
/// --seed + k on the --camera-px grid; at --bad-at it writes one with a NaN pixel instead).
/// With --record it reads sealing/Leakage from every sealing shard, merges the parts by
/// segment name and writes one line per segment and step, sorted by name, doubles in
/// hexfloat: "<step> <stamp> <segment> <leak_area_m2> <mean_gap_m>", so that two runs
/// compare byte for byte. A segment given by two parts, or missing, fails the run.

#include <cstdio>
#include <fstream>
#include <limits>
#include <map>

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "climbsim/errors.hpp"
#include "climbsim/lockstep_participant.hpp"
#include "climbsim/logging.hpp"
#include "climbsim/main_guard.hpp"
#include "scenePubSubTypes.h"
#include "sealingPubSubTypes.h"
#include "sealing_surfaces.hpp"
#include "sealing_translate.hpp"
#include "participant/exact_text.hpp"

using climbsim::records::hexText;

int main(int argc, char** argv) {
  using namespace climbsim;
  using namespace climbsim::sealing;
  CLI::App app{"climbsim-test-depth-feeder: feeds and records climbsim-sealing in tests"};
  ParticipantOptions options;
  int camera_px = 256;
  double view_m = 0.80;
  std::uint64_t seed = 1;
  std::int64_t bad_at = -1;
  std::size_t segment_count = 18;
  int distinct = 0;
  std::string record_file;
  options.addOptions(app);
  app.add_option("--camera-px", camera_px, "image width = height [px]")->check(CLI::Range(1, 1024));
  app.add_option("--view-m", view_m, "image width on the wall [m]");
  app.add_option("--seed", seed, "surface of step k: randomSurface(seed + k)");
  app.add_option("--distinct", distinct, "cycle through this many surfaces (0: a new one every step)");
  app.add_option("--bad-at", bad_at, "at this step write an image with a NaN pixel");
  app.add_option("--record", record_file, "read sealing/Leakage and write the merged parts here");
  app.add_option("--segments", segment_count, "with --record: the number of segments every step must cover");
  return guardedMain(app, argc, argv, "test-depth-feeder", [&]() -> int {
    initLogging(options.name);
    const PixelGrid grid{camera_px, camera_px, view_m / camera_px};
    options.dds.largest_sample_bytes = imageSampleBytes(camera_px, camera_px);
    LockstepParticipant participant(options);
    auto& depth = participant.output<DepthImagePubSubType>(topic::kDepthImage);
    StampedInput<LeakagePubSubType>* leakage = nullptr;
    std::ofstream record;
    if (!record_file.empty()) {
      record.open(record_file, std::ios::trunc);
      if (!record) throw ConfigError("--record = '" + record_file + "': cannot write it");
      leakage = &participant.input<LeakagePubSubType>(topic::kLeakage);
    }
    std::map<std::uint64_t, climbsim::DepthImage> cache;
    const int code = participant.run([&](const StepContext& ctx) {
      if (leakage != nullptr) {
        std::map<std::string, std::pair<double, double>> merged;
        std::uint64_t stamp = 0;
        for (const auto& part : leakage->get(ctx)) {
          stamp = part.step();
          for (const auto& s : part.segments()) {
            if (!merged.emplace(s.segment().c_str(), std::make_pair(s.leak_area_m2(), s.mean_gap_m())).second) {
              throw std::runtime_error(std::string("segment ") + s.segment().c_str() + " given by two parts");
            }
          }
        }
        if (!merged.empty() && merged.size() != segment_count) {
          throw std::runtime_error("step " + std::to_string(ctx.step) + ": the parts cover " +
                                   std::to_string(merged.size()) + " segments, expected " +
                                   std::to_string(segment_count));
        }
        for (const auto& [name, values] : merged) {
          record << ctx.step << ' ' << stamp << ' ' << name << ' ' << hexText(values.first) << ' ' << hexText(values.second)
                 << '\n';
        }
      }
      const std::uint64_t surface = distinct > 0 ? ctx.step % static_cast<std::uint64_t>(distinct) : ctx.step;
      auto it = cache.find(surface);
      if (it == cache.end()) {
        auto sample = depthImageToIdl(testing::randomSurface(grid, seed + surface), -0.05, 0.05);
        if (distinct <= 0) cache.clear();
        it = cache.emplace(surface, std::move(sample)).first;
      }
      if (static_cast<std::int64_t>(ctx.step) == bad_at) {
        auto bad = it->second;
        bad.height_m()[bad.height_m().size() / 2] = std::numeric_limits<float>::quiet_NaN();
        depth.write(ctx, bad);
      } else {
        depth.write(ctx, it->second);
      }
    });
    record.flush();
    return code;
  });
}
