#pragma once
/// @file
/// The rasteriser's inner kernel, one build per instruction set (raster_kernel.inc). Plain
/// data and declarations only: this header is compiled with different -m flags.

namespace climbsim::scene {

/// Triangles per batch of TriangleIndex (coordinate rows of 16 floats).
constexpr int kRasterBatchLanes = 16;

/// One depth frame as the kernel sees it.
struct RasterFrame {
  int W, H;          ///< image size [px]
  float near, far;   ///< z_C limits [m]
  float* z_buffer;   ///< W * H, row-major, raised to the highest z_C <= near per pixel centre
  float A[9];        ///< (u, v, z_C) = A (p_F - o) + (b_u, b_v, 0), row-major; u, v in pixels
  float o[3];        ///< camera origin in F [m]
  float b_u, b_v;
  /// The pixels written: columns c_lo..c_hi, rows r_lo..r_hi (the whole image or a tile). The
  /// triangles are classified and evaluated as for the whole image, so a tile's pixels are the
  /// whole image's bit for bit.
  int c_lo, c_hi, r_lo, r_hi;
  /// W * H bytes, 0 for a pixel not to write (PixelMask::bytes()), or null: every pixel.
  const unsigned char* mask;
  /// With a mask: the mask over 2 x 2 pixels (PixelMask::quads(), 3 bytes readable past its
  /// end), by which the default kernel tests a small triangle's (up to) 2 x 2 centres before its
  /// set-up, so that a triangle with no centre in the mask is passed over.
  const unsigned char* mask_quads;
  /// With a mask: its summed-area table of occupied blocks of block_px x block_px pixels,
  /// (blocks_y + 1) x (blocks_x + 1) (PixelMask), so that a triangle far from every pixel of
  /// the mask is passed over before its set-up.
  const unsigned* block_sum;
  int block_px, blocks_x, blocks_y;
  /// true: the reference kernel (each pixel step of a batch's small triangles raises its
  /// covered centres lane by lane); false: the covered centres are collected over a call's
  /// batches and raised in one pass, in the same order (the same image bit for bit).
  bool reference;
  /// If not null: increased by the triangles set up (edge functions and pixel tests): those in
  /// view and, with a mask, on the default kernel, the small ones whose box holds a pixel of it.
  unsigned long long* set_up;
};

/// The sample passes of area-weighted edge pixels as the kernel sees them: `samples` cameras
/// that differ only by their origin, each drawn as its own pass would be (RasterFrame's
/// arithmetic, frame.o replaced by the sample's origin), each written only at the edge pixels.
struct SampleFrame {
  /// Sample 0's frame: A, b_u, b_v are every sample's; its mask holds the edge pixels, its
  /// block sums pass over a triangle far from all of them; z_buffer and o are not read.
  RasterFrame frame;
  int samples;             ///< n
  int stride;              ///< n rounded up to kRasterBatchLanes: the samples of an edge pixel
  const float* o[3];       ///< per component, `stride` origins in F [m] (sample k's at k; padding: sample 0's)
  float o_lo[3], o_hi[3];  ///< per component, the least and the greatest origin of the samples [m]
  const int* edge_of;      ///< W * H: the edge pixel's index e, or -1
  /// Edge pixel e's sample k: z[e * stride + k], raised as a pass's z-buffer at that pixel;
  /// order[e * stride + k], where in the passes' order of writes the value was written (of equal
  /// values, +0 and -0, the first written is kept as the pass keeps it).
  float* z;
  int* order;
  unsigned long long* set_up;  ///< increased by the triangles set up (for every sample at once)
};

/// Rasterise `count` consecutive batches (each kRasterBatchLanes triangles, corners x0[16]
/// y0[16] z0[16] x1[16] ... z2[16] in F [m]) into frame.z_buffer. Same result from every variant.
void rasterizeBatchGeneric(const RasterFrame& frame, const float* batches, unsigned count);
void rasterizeBatchAvx2(const RasterFrame& frame, const float* batches, unsigned count);    ///< needs AVX2
void rasterizeBatchAvx512(const RasterFrame& frame, const float* batches, unsigned count);  ///< needs AVX-512 F and DQ

/// Raise the edge pixels' samples of `frame` by `count` consecutive batches, the first of which
/// is batch `first_batch` of all the passes draw (< 2^22). Each sample's values and order of
/// writes are those of rasterizeBatch* with that sample's frame, restricted to the edge pixels.
void sampleEdgesGeneric(const SampleFrame& frame, const float* batches, unsigned count, unsigned first_batch);
void sampleEdgesAvx2(const SampleFrame& frame, const float* batches, unsigned count, unsigned first_batch);
void sampleEdgesAvx512(const SampleFrame& frame, const float* batches, unsigned count, unsigned first_batch);

/// The edge decision (area_sampling.hpp: edgePixels) at the inner pixels c0 .. c1 - 1 of a row of
/// centre heights [m] (rows up, mid, down of a W-wide image; 1 <= c0 <= c1 <= W - 1, the row
/// neither the first nor the last): bit i of bends[i / 64] (bit i % 64) set where pixel c0 + i
/// has a second difference (along the row, the column or a diagonal) of magnitude above
/// threshold_m, as the double expressions decide it; (c1 - c0 + 63) / 64 words, overwritten.
/// Every variant sets the same bits.
void bendingPixelsGeneric(const float* up, const float* mid, const float* down, int c0, int c1, double threshold_m,
                          unsigned long long* bends);
void bendingPixelsAvx2(const float* up, const float* mid, const float* down, int c0, int c1, double threshold_m,
                       unsigned long long* bends);
void bendingPixelsAvx512(const float* up, const float* mid, const float* down, int c0, int c1, double threshold_m,
                         unsigned long long* bends);

}  // namespace climbsim::scene
