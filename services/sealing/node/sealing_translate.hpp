#pragma once
/// @file
/// Translators between the sealing topics (idl/scene.idl DepthImage, idl/sealing.idl Leakage
/// and SealingImage) and the sealing model. Pure functions: no DDS entity, tested without a
/// network. Stamp fields (source, step, t_ns) of stamped outputs are left to
/// StampedOutput::write.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "climbsim/topic_names.hpp"
#include "climbsim/shard_tiles/depth_grid.hpp"
#include "leakage.hpp"
#include "scene.h"
#include "sealing.h"

namespace climbsim::sealing {

/// Topic names: the one list of common/include/climbsim/topic_names.hpp (topic::kLeakage, ...).
namespace topic = climbsim::topic;

/// The pixels `sample` holds: its tile, or the whole image (tile_rows = tile_cols = 0 also
/// stands for the whole image).
PixelBox tileOf(const climbsim::DepthImage& sample);

/// The height no pixel of `sample`'s image exceeds [m]: near_m - headroom_m (the expression a
/// tile renderer chose its tile for, so that both get the same double).
inline double heightBound_m(const climbsim::DepthImage& sample) { return sample.near_m() - sample.headroom_m(); }

/// "" if `runs` (DepthImage.mask_runs: start raster index and length per run) are runs along
/// single rows of `tile` of an image `width_px` wide, ascending and not overlapping, else one
/// line naming the first bad run. If "" and `pixels` is given, *pixels = their pixel count.
std::string checkMaskRuns(const std::vector<std::uint32_t>& runs, int width_px, const PixelBox& tile,
                          std::size_t* pixels = nullptr);

/// Whether every raster pixel of `pixels` (ascending) lies in one of `runs` (checked by
/// checkMaskRuns): whether a masked tile holds every pixel a shard reads.
bool maskRunsCover(const std::vector<std::uint32_t>& runs, const std::vector<std::uint32_t>& pixels);

/// Raster index (row * width_px + col) of the image pixel that value `i` of `sample`'s height_m
/// holds (its tile row-major, or its mask runs in order); `tile` = tileOf(sample).
std::size_t rasterOfValue(const climbsim::DepthImage& sample, const PixelBox& tile, std::size_t i);

/// "" if `sample` is a usable depth image (or tile of one) for a camera of `camera`'s size and
/// pixel size, else one line naming the problem: size or pixel size differing from the
/// camera's, a tile outside the image, bad mask runs (checkMaskRuns), a value count other than
/// the tile's (or its mask runs') pixels, a headroom_m not in [0, near_m - far_m],
/// near_m <= far_m or non-finite, a non-finite pixel, or a pixel outside [far_m, near_m -
/// headroom_m] by more than 1 µm (the camera clamps to [far_m, near_m]; the renderer bounds by
/// the headroom). If "" and `highest` is given, *highest =
/// the highest pixel of the sample (found in the same pass over the pixels). Support heights
/// (support_px, support_m) must be as many as their pixels, ascending inside the tile, in the
/// pixels' range; *highest bounds them too.
std::string checkDepthImage(const climbsim::DepthImage& sample, const PixelGrid& camera, float* highest = nullptr);

/// The heights of `sample` as the model's depth image (no checks: checkDepthImage first),
/// into `depth`: a whole image replaces it; a tile overwrites its pixels (a masked tile: its
/// runs' pixels) of the last image of the same size (far_m elsewhere the first time), and its
/// support heights replace the last ones. upper_bound_m = the highest pixel or support received.
void depthGridFromIdl(const climbsim::DepthImage& sample, DepthGrid& depth);
/// The same, taking the support heights' buffers and a whole image's instead of copying them
/// (the sample is left with depth's old ones) and with upper_bound_m = `highest` (from
/// checkDepthImage), without another pass over the pixels.
void depthGridFromIdl(climbsim::DepthImage&& sample, DepthGrid& depth, float highest);
/// The same into a new grid.
DepthGrid depthGridFromIdl(const climbsim::DepthImage& sample);

/// A DepthImage of `depth` (its support heights too) with the camera range [far_m, near_m]
/// (for feeders and tests).
climbsim::DepthImage depthImageToIdl(const DepthGrid& depth, double far_m, double near_m);

/// A Leakage part with the segments `indices` (geometry order) of `names` and `leaks`.
/// std::invalid_argument if more than 64 segments or a name longer than 31 characters.
climbsim::Leakage leakageToIdl(const std::vector<std::string>& names, const std::vector<SegmentLeak>& leaks,
                               const std::vector<std::size_t>& indices);

/// A SealingImage of `kind` ("edges" or "gaps") holding the PNG bytes `png`, stamped with
/// `source`, `step` and `t_ns` (it is written outside the stamped outputs, best effort).
climbsim::SealingImage sealingImageToIdl(const std::string& source, std::uint64_t step, std::int64_t t_ns,
                                         const std::string& kind, const std::vector<unsigned char>& png);

}  // namespace climbsim::sealing
