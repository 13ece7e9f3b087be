#include "depth_rasterizer.hpp"

#include <algorithm>
#include <limits>

#include <cmath>
#include <cstring>
#include <stdexcept>

#include "raster_kernel.hpp"

namespace climbsim::scene {

static_assert(TriangleIndex::kBatchLanes == kRasterBatchLanes, "the kernels read the index's batches");

namespace {

using Kernel = void (*)(const RasterFrame&, const float*, unsigned);

bool supports(RasterKernel kernel) {
  __builtin_cpu_init();
  switch (kernel) {
    case RasterKernel::kAvx512:
      return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq");
    case RasterKernel::kAvx2:
      return __builtin_cpu_supports("avx2");
    default:
      return true;
  }
}

RasterKernel widest() {
  return supports(RasterKernel::kAvx512) ? RasterKernel::kAvx512
         : supports(RasterKernel::kAvx2) ? RasterKernel::kAvx2
                                         : RasterKernel::kGeneric;
}

Kernel function(RasterKernel kernel) {
  switch (kernel) {
    case RasterKernel::kAvx512:
      return rasterizeBatchAvx512;
    case RasterKernel::kAvx2:
      return rasterizeBatchAvx2;
    default:
      return rasterizeBatchGeneric;
  }
}

}  // namespace

bool rasterKernelSupported(RasterKernel kernel) { return supports(kernel); }

const char* rasterKernelName() {
  static const RasterKernel best = widest();
  return best == RasterKernel::kAvx512 ? "avx512" : best == RasterKernel::kAvx2 ? "avx2" : "generic";
}

double depthTopBound(const TriangleIndex& index, const Pose& T_C_F, const DepthCameraParams& camera,
                     const std::vector<char>& slot_excluded) {
  const double s = camera.pixel_size_m;
  // The whole image's view, one pixel wider on each side (as a tile's view is).
  const double half_x = 0.5 * camera.width_px * s + s, half_y = 0.5 * camera.height_px * s + s;
  const Eigen::Matrix3d abs_R = T_C_F.linear().cwiseAbs();
  double top = -std::numeric_limits<double>::infinity();
  index.forEachLeafInView(T_C_F.linear(), T_C_F.translation(), half_x, half_y, camera.far_m, camera.near_m,
                          [&](const TriangleIndex::Leaf& leaf) {
                            if (!slot_excluded.empty() && slot_excluded[leaf.slot]) return;
                            const double c = T_C_F.linear().row(2).dot(leaf.box_F.center().cast<double>()) +
                                             T_C_F.translation().z();
                            const double e = abs_R.row(2).dot(0.5 * leaf.box_F.sizes().cast<double>());
                            top = std::max(top, c + e);
                          });
  return top;
}

namespace {

// The kernel's view of one frame: p_F -> (u, v, z) = A (p_F - o_F) + b with o_F the camera
// origin in F: u = x_C / s + W/2 - 0.5 (column of a centre), v = -y_C / s + H/2 - 0.5.
// Subtracting o_F first keeps float arithmetic accurate far from F's origin.
RasterFrame frameOf(const Pose& T_C_F, const DepthCameraParams& camera, float* z_buffer, bool reference) {
  const int W = camera.width_px;
  const int H = camera.height_px;
  const double s = camera.pixel_size_m;
  RasterFrame frame{};
  frame.W = W;
  frame.H = H;
  frame.near = static_cast<float>(camera.near_m);
  frame.far = static_cast<float>(camera.far_m);
  frame.z_buffer = z_buffer;
  frame.reference = reference;
  Eigen::Matrix3d A = T_C_F.linear();
  A.row(0) /= s;
  A.row(1) /= -s;
  const Eigen::Vector3d o_F = -(T_C_F.linear().transpose() * T_C_F.translation());
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) frame.A[3 * row + col] = static_cast<float>(A(row, col));
    frame.o[row] = static_cast<float>(o_F(row));
  }
  frame.b_u = static_cast<float>(0.5 * W - 0.5);
  frame.b_v = static_cast<float>(0.5 * H - 0.5);
  const PixelTile& tile = camera.tile;
  frame.c_lo = tile.whole() ? 0 : tile.col0;
  frame.c_hi = tile.whole() ? W - 1 : tile.col0 + tile.cols - 1;
  frame.r_lo = tile.whole() ? 0 : tile.row0;
  frame.r_hi = tile.whole() ? H - 1 : tile.row0 + tile.rows - 1;
  const PixelMask* mask = tile.mask.get();
  frame.mask = mask ? mask->bytes() : nullptr;
  frame.mask_quads = mask ? mask->quads() : nullptr;
  static_assert(sizeof(unsigned) == sizeof(std::uint32_t));
  frame.block_sum = mask ? mask->blockSums() : nullptr;
  frame.block_px = PixelMask::kBlockPx;
  frame.blocks_x = mask ? mask->blocksX() : 0;
  frame.blocks_y = mask ? mask->blocksY() : 0;
  return frame;
}

Kernel kernelOf(RasterKernel variant) {
  static const RasterKernel best = widest();
  if (variant != RasterKernel::kAuto && !supports(variant)) throw std::invalid_argument("rasteriser: kernel not supported by this CPU");
  return function(variant == RasterKernel::kAuto ? best : variant);
}

using SampleKernel = void (*)(const SampleFrame&, const float*, unsigned, unsigned);

SampleKernel sampleKernelOf(RasterKernel variant) {
  kernelOf(variant);  // checks the CPU runs it
  const RasterKernel used = variant == RasterKernel::kAuto ? widest() : variant;
  return used == RasterKernel::kAvx512 ? sampleEdgesAvx512 : used == RasterKernel::kAvx2 ? sampleEdgesAvx2 : sampleEdgesGeneric;
}

}  // namespace

BendingPixelsKernel bendingPixelsKernel(RasterKernel variant) {
  kernelOf(variant);  // checks the CPU runs it
  const RasterKernel used = variant == RasterKernel::kAuto ? widest() : variant;
  return used == RasterKernel::kAvx512 ? bendingPixelsAvx512 : used == RasterKernel::kAvx2 ? bendingPixelsAvx2 : bendingPixelsGeneric;
}

void EdgeSampleBuffer::start(const std::vector<std::uint32_t>& edges, int width_px, int height_px, int samples) {
  const std::size_t pixels = static_cast<std::size_t>(width_px) * height_px;
  if (edge_of_.size() != pixels) {
    edge_of_.assign(pixels, -1);
  } else {
    for (const std::uint32_t i : edges_) edge_of_[i] = -1;
  }
  edges_ = edges;
  for (std::size_t e = 0; e < edges.size(); ++e) edge_of_[edges[e]] = static_cast<int>(e);
  samples_ = samples;
  stride_ = (samples + kRasterBatchLanes - 1) / kRasterBatchLanes * kRasterBatchLanes;
  z_.assign(edges.size() * static_cast<std::size_t>(stride_), -std::numeric_limits<float>::infinity());
  order_.assign(z_.size(), std::numeric_limits<int>::max());
  batches_drawn_ = 0;
}

void rasterizeEdgeSamples(const TriangleIndex& index, const std::vector<BatchRun>& runs,
                          const std::vector<Pose>& T_C_F, const DepthCameraParams& camera, EdgeSampleBuffer& buffer,
                          RasterKernel variant, RasterCounters* counters) {
  if (static_cast<int>(T_C_F.size()) != buffer.samples_) {
    throw std::invalid_argument("rasteriser: one camera per sample expected");
  }
  const SampleKernel kernel = sampleKernelOf(variant);
  SampleFrame frame{};
  frame.frame = frameOf(T_C_F.front(), camera, nullptr, false);
  frame.samples = buffer.samples_;
  frame.stride = buffer.stride_;
  std::vector<float> origins[3];
  for (int j = 0; j < 3; ++j) {
    origins[j].assign(static_cast<std::size_t>(frame.stride), frame.frame.o[j]);
    frame.o[j] = origins[j].data();
    frame.o_lo[j] = frame.o_hi[j] = frame.frame.o[j];
  }
  for (std::size_t k = 0; k < T_C_F.size(); ++k) {
    const RasterFrame sample = frameOf(T_C_F[k], camera, nullptr, false);
    // A translated camera keeps its rotation: the same matrix bit for bit.
    if (std::memcmp(sample.A, frame.frame.A, sizeof(sample.A)) != 0) {
      throw std::invalid_argument("rasteriser: the sample cameras must differ only by their origin");
    }
    for (int j = 0; j < 3; ++j) {
      origins[j][k] = sample.o[j];
      frame.o_lo[j] = std::min(frame.o_lo[j], sample.o[j]);
      frame.o_hi[j] = std::max(frame.o_hi[j], sample.o[j]);
    }
  }
  frame.edge_of = buffer.edge_of_.data();
  frame.z = buffer.z_.data();
  frame.order = buffer.order_.data();
  unsigned long long set_up = 0;
  frame.set_up = &set_up;
  for (const BatchRun& run : runs) {
    constexpr std::uint32_t kMostBatches = 1u << 22;  // the order's field (edge_sample_kernel.inc)
    if (run.batch_count >= kMostBatches - buffer.batches_drawn_) {
      throw std::invalid_argument("rasteriser: more than 2^22 batches in the sample passes' view");
    }
    kernel(frame, index.batchData_F(run.first_batch), run.batch_count, buffer.batches_drawn_);
    buffer.batches_drawn_ += run.batch_count;
  }
  if (counters) counters->sample_triangles_set_up += set_up;
}

std::vector<BatchRun> batchesInView(const TriangleIndex& index, const Pose& T_C_F, const DepthCameraParams& camera,
                                    const std::vector<char>& slot_excluded, int margin_px, bool reference,
                                    RasterCounters* counters) {
  const int W = camera.width_px;
  const int H = camera.height_px;
  const double s = camera.pixel_size_m;
  const PixelTile& tile = camera.tile;
  const int c_lo = tile.whole() ? 0 : tile.col0, c_hi = tile.whole() ? W - 1 : tile.col0 + tile.cols - 1;
  const int r_lo = tile.whole() ? 0 : tile.row0, r_hi = tile.whole() ? H - 1 : tile.row0 + tile.rows - 1;
  // The view volume of the pixels written: the tile's box (one pixel wider on each side, and
  // margin_px more), as a box about its own centre (x_C, y_C) = (cx, cy).
  const double cx = 0.5 * (c_lo + c_hi + 1 - W) * s;
  const double cy = 0.5 * (H - r_lo - r_hi - 1) * s;
  const double grown = (tile.whole() ? 0.0 : s) + margin_px * s;
  const double half_x = 0.5 * (c_hi - c_lo + 1) * s + grown;
  const double half_y = 0.5 * (r_hi - r_lo + 1) * s + grown;
  const Eigen::Vector3d a_CF = T_C_F.translation() - Eigen::Vector3d(cx, cy, 0.0);
  const PixelMask* mask = tile.mask.get();
  // With a mask: a leaf whose pixel box (of its box's mapped box, one pixel wider for rounding)
  // holds no pixel of the mask cannot write any of them (the reference tests the mask's blocks).
  // From the box's mapped box about the view's centre (c_view = A c_F + a_CF, e = |A| h_F).
  const double u_0 = cx / s + 0.5 * W - 0.5, v_0 = -cy / s + 0.5 * H - 0.5;
  const auto meetsMaskMapped = [&](const Eigen::Vector3d& c_view, const Eigen::Vector3d& e) {
    const double u_lo = (c_view.x() - e.x()) / s + u_0, u_hi = (c_view.x() + e.x()) / s + u_0;
    const double v_lo = (-c_view.y() - e.y()) / s + v_0, v_hi = (-c_view.y() + e.y()) / s + v_0;
    const int m = 1 + margin_px;
    const int r0 = static_cast<int>(std::floor(v_lo)) - m, r1 = static_cast<int>(std::ceil(v_hi)) + m;
    const int c0 = static_cast<int>(std::floor(u_lo)) - m, c1 = static_cast<int>(std::ceil(u_hi)) + m;
    return reference ? mask->mayMeet(r0, r1, c0, c1) : mask->mayMeet(r0, r1, c0, c1) && mask->meets(r0, r1, c0, c1);
  };
  // A batch's box in view (as forEachLeafInView tests a leaf's).
  const ViewVolume view{T_C_F.linear(), a_CF, half_x, half_y, camera.far_m, camera.near_m};
  std::vector<BatchRun> runs;
  const auto keep = [&](std::uint32_t first, std::uint32_t count, std::uint64_t leaves) {
    if (count > 0) runs.push_back({first, count});
    if (!counters) return;
    counters->leaves += leaves;
    counters->triangles += std::uint64_t{count} * kRasterBatchLanes;
  };
  index.forEachLeafInView(T_C_F.linear(), a_CF, half_x, half_y, camera.far_m, camera.near_m,
                          [&](const TriangleIndex::Leaf& leaf, bool wholly_in_view, const Eigen::Vector3d& c_leaf,
                              const Eigen::Vector3d& e_leaf) {
                            if (!slot_excluded.empty() && slot_excluded[leaf.slot]) return;
                            if (mask && !meetsMaskMapped(c_leaf, e_leaf)) return;
                            if (reference || wholly_in_view) {
                              keep(leaf.first_batch, leaf.batch_count, 1);
                              return;
                            }
                            // A leaf partly in view: only its batches that may write a pixel
                            // (in view, and holding a pixel of the mask), runs of consecutive ones.
                            std::uint32_t first = leaf.first_batch, kept = 0;
                            for (std::uint32_t b = leaf.first_batch; b < leaf.first_batch + leaf.batch_count; ++b) {
                              const Eigen::AlignedBox3f& box = index.batchBox_F(b);
                              Eigen::Vector3d c, e;
                              view.map(box, c, e);
                              if (view.placeMapped(c, e) != 0 && (!mask || meetsMaskMapped(c, e))) {
                                if (kept == 0) first = b;
                                ++kept;
                              } else {
                                keep(first, kept, 0);
                                kept = 0;
                              }
                            }
                            keep(first, kept, 1);
                          });
  return runs;
}

void rasterizeBatches(const TriangleIndex& index, const std::vector<BatchRun>& runs, const Pose& T_C_F,
                      const DepthCameraParams& camera, std::vector<float>& z_buffer, RasterKernel variant,
                      bool reference, RasterCounters* counters) {
  RasterFrame frame = frameOf(T_C_F, camera, z_buffer.data(), reference);
  unsigned long long set_up = 0;
  if (counters) frame.set_up = &set_up;
  const Kernel kernel = kernelOf(variant);
  for (const BatchRun& run : runs) kernel(frame, index.batchData_F(run.first_batch), run.batch_count);
  if (counters) counters->triangles_set_up += set_up;
}

void rasterizeDepth(const TriangleIndex& index, const Pose& T_C_F, const DepthCameraParams& camera,
                    const std::vector<char>& slot_excluded, std::vector<float>& z_buffer, RasterKernel variant,
                    RasterCounters* counters, bool reference) {
  rasterizeBatches(index, batchesInView(index, T_C_F, camera, slot_excluded, 0, reference, counters), T_C_F, camera,
                   z_buffer, variant, reference, counters);
}

}  // namespace climbsim::scene
