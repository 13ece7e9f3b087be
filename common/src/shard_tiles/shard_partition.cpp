#include "climbsim/shard_tiles/shard_partition.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "climbsim/errors.hpp"

namespace climbsim::sealing {

std::vector<std::vector<std::size_t>> partitionSegments(const StripMasks& masks, std::size_t count) {
  const std::size_t segments = masks.segmentCount();
  const auto bad = [&](const std::string& why) {
    return ConfigError("--shard: " + std::to_string(count) + " shards: " + why);
  };
  if (count == 0) throw bad("need at least one");
  if (count > segments) {
    throw bad("the robot has only " + std::to_string(segments) + " sealing segments, so some shards would get none");
  }
  const PixelGrid& grid = masks.grid();
  const auto& pixels = masks.sealingPixels();
  std::vector<double> angle(segments);
  std::size_t total = 0;
  for (std::size_t s = 0; s < segments; ++s) {
    double x = 0.0;
    double y = 0.0;
    for (const std::uint32_t k : masks.segmentPixels(s)) {
      x += grid.xOfColumn_m(static_cast<double>(pixels[k] % grid.width_px));
      y += grid.yOfRow_m(static_cast<double>(pixels[k] / grid.width_px));
    }
    angle[s] = std::atan2(y, x);
    total += masks.segmentPixels(s).size();
  }
  std::vector<std::size_t> order(segments);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return angle[a] < angle[b]; });

  std::vector<std::vector<std::size_t>> shards(count);
  double before = 0.0;
  for (const std::size_t s : order) {
    const double own = static_cast<double>(masks.segmentPixels(s).size());
    const auto shard = std::min(count - 1, static_cast<std::size_t>(count * (before + own / 2.0) / total));
    shards[shard].push_back(s);
    before += own;
  }
  for (std::size_t i = 0; i < count; ++i) {
    if (shards[i].empty()) throw bad("shard " + std::to_string(i) + " would get no segment (the segments are too unequal)");
    std::sort(shards[i].begin(), shards[i].end());
  }
  return shards;
}

ShardSpec ShardSpec::parse(const std::string& text) {
  const auto slash = text.find('/');
  auto bad = [&](const std::string& why) { return ConfigError("--shard = '" + text + "': " + why); };
  if (slash == std::string::npos || slash == 0 || slash + 1 == text.size()) throw bad("expected I/N, e.g. 0/2");
  auto number = [&](const std::string& part) {
    if (part.find_first_not_of("0123456789") != std::string::npos || part.size() > 6) {
      throw bad("expected I/N with whole numbers, e.g. 0/2");
    }
    return static_cast<std::size_t>(std::stoul(part));
  };
  ShardSpec spec{number(text.substr(0, slash)), number(text.substr(slash + 1))};
  if (spec.count == 0 || spec.index >= spec.count) throw bad("need 0 <= I < N");
  return spec;
}

std::vector<std::size_t> ShardSpec::segments(const StripMasks& masks) const {
  try {
    return partitionSegments(masks, count).at(index);
  } catch (const ConfigError& e) {
    throw ConfigError("--shard = '" + std::to_string(index) + "/" + std::to_string(count) + "': " +
                      std::string(e.what()).substr(std::string("--shard: ").size()));
  }
}

}  // namespace climbsim::sealing
