#include "sealing_node.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/imgcodecs.hpp>
#include <spdlog/spdlog.h>

#include "climbsim/errors.hpp"
#include "sealing_pictures.hpp"
#include "climbsim/shard_tiles/shard_partition.hpp"
#include "sealing_translate.hpp"

namespace climbsim::sealing {

SealingNode::SealingNode(const SealingModel& model, const ShardSpec& shard)
    : model_(model), shard_(shard), state_(model.initialState(shard.segments(model.masks()))) {}

const SealingNode::Needed& SealingNode::needed(double height_bound_m) const {
  // checkDepthImage admits pixels up to 1 µm above the bound. Bounds that give the same count
  // give the same pixels: a renderer's bounds come from a few of them (whole bands).
  const double upper_bound_m = height_bound_m + 1e-6;
  const std::size_t count = model_.neededCount(state_.segments, upper_bound_m);
  auto found = needed_.find(count);
  if (found == needed_.end()) {
    found = needed_
                .emplace(count, Needed{model_.neededBox(state_.segments, upper_bound_m),
                                       model_.neededPixels(state_.segments, upper_bound_m)})
                .first;
  }
  return found->second;
}

PixelBox SealingNode::neededBox(double height_bound_m) const { return needed(height_bound_m).box; }

bool SealingNode::holdsNeededPixels(const climbsim::DepthImage& sample, const Needed& need) const {
  const auto& runs = sample.mask_runs();
  if (runs.empty()) return true;  // every pixel of its box
  if (runs == covering_runs_ && &need == covering_need_) return true;  // a renderer's runs repeat
  // Bad runs are not passed over: checkDepthImage names them.
  if (!checkMaskRuns(runs, model_.grid().width_px, tileOf(sample)).empty()) return true;
  if (!maskRunsCover(runs, need.pixels)) return false;
  covering_runs_ = runs;
  covering_need_ = &need;
  return true;
}

climbsim::Leakage SealingNode::step(std::vector<climbsim::DepthImage> depth_images) {
  climbsim::DepthImage* chosen = nullptr;
  float chosen_highest = 0.0f;
  std::string tiles_seen;
  for (auto& sample : depth_images) {
    // A tile for another shard (climbsim-scene --tile): not ours, and not worth checking its
    // pixels (the box first: it costs nothing).
    const PixelBox tile = tileOf(sample);
    // (Only for a valid header: checkDepthImage names a bad one.)
    const bool bound_valid = sample.headroom_m() >= 0.0 && std::isfinite(heightBound_m(sample)) &&
                             heightBound_m(sample) >= sample.far_m();
    if (bound_valid && PixelBox{0, 0, model_.grid().height_px, model_.grid().width_px}.contains(tile) &&
        static_cast<int>(sample.width_px()) == model_.grid().width_px &&
        static_cast<int>(sample.height_px()) == model_.grid().height_px) {
      const Needed& need = needed(heightBound_m(sample));
      const bool box_held = tile.contains(need.box);
      if (!box_held || !holdsNeededPixels(sample, need)) {
        tiles_seen += std::string(tiles_seen.empty() ? "" : ", ") + "'" + sample.source().c_str() + "' " + tile.text() +
                      (box_held ? " masked to other pixels" : "");
        continue;
      }
    }
    // Every pixel checked (whether or not this shard reads it), and the highest found in the
    // same pass: the one pass over the image before the adaptation.
    float highest = 0.0f;
    const std::string why = checkDepthImage(sample, model_.grid(), &highest);
    if (!why.empty()) {
      ++dropped_;
      spdlog::warn("{} from '{}' at step {}: {}; dropped ({} so far), last valid leakage held", topic::kDepthImage,
                   sample.source().c_str(), sample.step(), why, dropped_);
      continue;
    }
    chosen = &sample;
    chosen_highest = highest;
  }
  if (chosen == nullptr && !tiles_seen.empty()) {
    throw ConfigError("sealing shard " + std::to_string(shard_.index) + "/" + std::to_string(shard_.count) +
                      " needs " + neededBox(heightBound_m(depth_images.front())).text() + " of the depth image; no " +
                      topic::kDepthImage + " covers them (" + tiles_seen +
                      "): run climbsim-scene --tile I/N with the shards' N");
  }
  SealingInputs inputs;
  if (chosen != nullptr) {
    if (!last_depth_) last_depth_.emplace();
    last_is_tile_ = !(tileOf(*chosen) == PixelBox{0, 0, model_.grid().height_px, model_.grid().width_px}) ||
                    !chosen->mask_runs().empty();
    // A whole image's pixels are taken, not copied (the samples are ours).
    depthGridFromIdl(std::move(*chosen), *last_depth_, chosen_highest);
    last_far_m_ = chosen->far_m();
    last_near_m_ = chosen->near_m();
    inputs.depth = &*last_depth_;
    inputs.far_m = last_far_m_;
  }
  const std::int64_t t_ns = chosen != nullptr ? chosen->t_ns() : 0;
  const SealingOutputs out = model_.step(state_, inputs, t_ns, 0);
  if (out.computed) warnNoSurface(t_ns);
  return leakageToIdl(model_.params().segment_names, out.leaks, state_.segments);
}

std::string SealingNode::sealOverNothingReason(std::int64_t t_ns) const {
  if (no_surface_warned_.empty()) return {};
  const std::size_t s = no_surface_warned_.front();
  return fmt::format("SEAL OVER NOTHING at t = {:.3f} s: segment '{}' hangs over nothing ({:.0f} % of its strip sees "
                     "no wall); the scenario ends runs on it (end_on.seal_over_nothing)",
                     static_cast<double>(t_ns) * 1e-9, model_.params().segment_names[s],
                     100.0 * state_.leaks[s].no_surface_share);
}

void SealingNode::warnNoSurface(std::int64_t t_ns) {
  for (const std::size_t s : state_.segments) {
    const SegmentLeak& leak = state_.leaks[s];
    if (leak.no_surface_share >= kNoSurfaceWarnShare &&
        std::find(no_surface_warned_.begin(), no_surface_warned_.end(), s) == no_surface_warned_.end()) {
      no_surface_warned_.push_back(s);
      const double basic_m2 = model_.closedLeaks()[s].leak_area_m2;
      spdlog::warn("sealing: at t = {:.3f} s segment '{}' hangs over nothing: {:.0f} % of its strip sees no wall "
                   "within {:.3f} m of the sealing plane (past the edge of the scene, or a hole deeper than the "
                   "camera's far limit); its leak is {:.3g} m^2{} (warned once per segment; summary.json "
                   "seal_over_nothing)",
                   static_cast<double>(t_ns) * 1e-9, model_.params().segment_names[s], 100.0 * leak.no_surface_share,
                   -last_far_m_, leak.leak_area_m2,
                   basic_m2 > 0.0 ? fmt::format(", {:.0f}x its basic leak", leak.leak_area_m2 / basic_m2) : "");
    }
  }
}

std::vector<std::pair<std::string, std::vector<unsigned char>>> SealingNode::pictures() const {
  std::vector<std::pair<std::string, std::vector<unsigned char>>> out;
  if (!last_depth_) return out;
  // A shard adapts only its region: the pictures show the whole sealing when it has the whole
  // image, else its region (NaN elsewhere).
  SealingResult whole;
  const bool partial = state_.last.adapted_px != model_.masks().sealingPixels().size();
  const SealingResult& shown = partial && !last_is_tile_ ? whole : state_.last;
  if (&shown == &whole) whole = model_.compute(*last_depth_);
  std::vector<unsigned char> png;
  cv::imencode(".png", edgesPicture(*last_depth_, model_.masks(), last_far_m_, last_near_m_), png);
  out.emplace_back("edges", png);
  cv::imencode(".png",
               gapsPicture(*last_depth_, model_.masks(), shown.sealing_m, model_.params().travel_m, last_far_m_,
                           last_near_m_),
               png);
  out.emplace_back("gaps", png);
  return out;
}

}  // namespace climbsim::sealing
