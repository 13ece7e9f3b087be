#pragma once
/// @file
/// The z-buffer depth camera: the triangles of a TriangleIndex under the camera window are
/// projected onto the pixel grid and each pixel centre covered by a triangle takes the
/// triangle's z_C there (barycentric interpolation), keeping the highest z_C <= near.

#include <cstdint>
#include <vector>

#include "depth_camera.hpp"
#include "triangle_index.hpp"
#include "climbsim/wall/triangle_mesh.hpp"

namespace climbsim::scene {

/// Raises z_buffer (W * H, row-major, start at -inf) at every pixel centre covered by a
/// triangle of `index` to that triangle's z_C, where it is <= near. T_C_F maps the index's
/// frame F into the camera frame C. Leaves whose slot has slot_excluded[slot] != 0 are
/// skipped. Covered means inside or on an edge: a pixel centre on an edge shared by two
/// triangles is covered by both (the edge functions are evaluated in one canonical vertex
/// order, so neighbours agree bit for bit and no pixel falls through a crack).
/// The inner kernel's variants; all give the same image bit for bit.
enum class RasterKernel {
  kAuto,     ///< the widest this CPU runs
  kGeneric,  ///< 4 lanes, any x86-64
  kAvx2,     ///< 8 lanes
  kAvx512,   ///< 16 lanes (AVX-512 F and DQ)
};

/// Whether this CPU runs the variant (kAuto and kGeneric: always).
bool rasterKernelSupported(RasterKernel kernel);
/// The variant kAuto stands for on this CPU: "avx512", "avx2" or "generic".
const char* rasterKernelName();

/// The edge decision's row kernel (raster_kernel.hpp: bendingPixels*) of a variant this CPU
/// runs (kAuto: the widest); every variant sets the same bits.
using BendingPixelsKernel = void (*)(const float* up, const float* mid, const float* down, int c0, int c1,
                                     double threshold_m, unsigned long long* bends);
BendingPixelsKernel bendingPixelsKernel(RasterKernel kernel);

/// The work of rasterizeDepth calls, counted (tests and benchmarks compare work, not time).
struct RasterCounters {
  std::uint64_t leaves = 0;     ///< leaves rasterised (box in the view volume of the pixels written, slot not excluded)
  std::uint64_t triangles = 0;  ///< triangles handed to the kernel (the leaves' batches x 16 lanes)
  /// Of those, in the passes over pixel centres: the triangles set up (in view and, with a mask,
  /// on the default path, the small ones whose box holds a pixel of it).
  std::uint64_t triangles_set_up = 0;
  /// Of those, in the sample passes of area-weighted edge pixels: the triangles set up (once
  /// for every sample), those whose pixel boxes over the samples meet an edge pixel's block.
  std::uint64_t sample_triangles_set_up = 0;
  RasterCounters& operator+=(const RasterCounters& o) {
    leaves += o.leaves;
    triangles += o.triangles;
    triangles_set_up += o.triangles_set_up;
    sample_triangles_set_up += o.sample_triangles_set_up;
    return *this;
  }
};

/// The highest z_C [m] of the triangles of `index` (in frame F, mapped to C by T_C_F) that may
/// lie in the view of the whole image of `camera` between far and near, from the boxes of the
/// index's leaves (an upper bound of every height the image can hold: a triangle's z_C never
/// exceeds its leaf box's top); -inf if none is in view. Leaves of excluded slots do not count.
double depthTopBound(const TriangleIndex& index, const Pose& T_C_F, const DepthCameraParams& camera,
                     const std::vector<char>& slot_excluded);

/// `counters`, if given, is increased by this call's work. `reference`: the reference kernel
/// (RenderOptions::reference_raster), the same image bit for bit.
/// Consecutive batches of a TriangleIndex: batchData_F(first_batch) .. + batch_count - 1.
struct BatchRun {
  std::uint32_t first_batch = 0;
  std::uint32_t batch_count = 0;
};

/// The batches of `index` (frame F, mapped to C by T_C_F) that may write a pixel of `camera`'s
/// image or tile (and mask), in the order rasterizeDepth draws them: its leaves in view
/// (excluded slots left out) whose pixel box holds a pixel of the mask (meets one of its
/// blocks with `reference`), and of a leaf partly in view only its batches whose box is in
/// view and holds a pixel of the mask (all of them with `reference`). `margin_px` widens the
/// view and the mask's reach by that many pixels: the batches then serve every camera moved
/// by less than that within the image plane. `counters`, if given, is increased by the leaves and triangles kept.
std::vector<BatchRun> batchesInView(const TriangleIndex& index, const Pose& T_C_F, const DepthCameraParams& camera,
                                    const std::vector<char>& slot_excluded, int margin_px, bool reference,
                                    RasterCounters* counters = nullptr);

/// Raises z_buffer as rasterizeDepth does, over the batches `runs` only (batchesInView), with
/// the camera at T_C_F. `counters`, if given: triangles_set_up increased.
void rasterizeBatches(const TriangleIndex& index, const std::vector<BatchRun>& runs, const Pose& T_C_F,
                      const DepthCameraParams& camera, std::vector<float>& z_buffer,
                      RasterKernel kernel = RasterKernel::kAuto, bool reference = false,
                      RasterCounters* counters = nullptr);

/// The sample passes' z-buffers at the edge pixels only (rasterizeEdgeSamples): for edge pixel
/// e (its index in the list given to start) and sample k, what a pass of sample k's camera
/// raises z_buffer[edges[e]] to.
class EdgeSampleBuffer {
 public:
  /// Before the passes: `samples` cameras over the raster pixels `edges` (ascending, not empty)
  /// of a W x H image, every value -inf.
  void start(const std::vector<std::uint32_t>& edges, int width_px, int height_px, int samples);
  /// Sample k of edge pixel e [m] (-inf where no triangle covers it).
  float at(std::size_t e, int k) const { return z_[e * static_cast<std::size_t>(stride_) + static_cast<std::size_t>(k)]; }

 private:
  friend void rasterizeEdgeSamples(const TriangleIndex&, const std::vector<BatchRun>&, const std::vector<Pose>&,
                                   const DepthCameraParams&, EdgeSampleBuffer&, RasterKernel, RasterCounters*);
  int samples_ = 0, stride_ = 0;
  std::vector<float> z_;
  std::vector<int> order_;                 // where in the passes' order of writes each value came
  std::vector<int> edge_of_;               // W * H: edge pixel index or -1
  std::vector<std::uint32_t> edges_;       // of the last start (their edge_of_ entries are set)
  std::uint32_t batches_drawn_ = 0;        // by the passes so far (the order of the next)
};

/// Raises `buffer` as rasterizeBatches over `runs` with the camera at T_C_F[k] raises sample k
/// (every k at once, the same values bit for bit), at the edge pixels only. The cameras differ
/// only by their origin (sample offsets within the image plane); `camera`'s tile has the edge
/// pixels as its mask (tileOf), `runs` are the batches that may write one of them for any sample
/// (batchesInView with a margin). Indices are drawn in the order of their calls. `counters`,
/// if given: sample_triangles_set_up increased.
void rasterizeEdgeSamples(const TriangleIndex& index, const std::vector<BatchRun>& runs,
                          const std::vector<Pose>& T_C_F, const DepthCameraParams& camera, EdgeSampleBuffer& buffer,
                          RasterKernel kernel = RasterKernel::kAuto, RasterCounters* counters = nullptr);

void rasterizeDepth(const TriangleIndex& index, const Pose& T_C_F, const DepthCameraParams& camera,
                    const std::vector<char>& slot_excluded, std::vector<float>& z_buffer,
                    RasterKernel kernel = RasterKernel::kAuto, RasterCounters* counters = nullptr,
                    bool reference = false);

}  // namespace climbsim::scene
