#include "depth_rasterizer.hpp"

#include <algorithm>
#include <cmath>

namespace climbsim::scene {

namespace {

// The vector helpers below are internal and inlined: the ABI note on 64-byte vectors
// returned without AVX does not concern any interface.
#pragma GCC diagnostic ignored "-Wpsabi"

// A batch of 8 triangles at a time (32-byte vectors: GCC 12 scalarises the comparisons of wider
// generic vectors). A fine wall has triangles about one pixel in size, so
// the per-triangle set-up dominates; doing it in vector lanes is what makes 500 frames/s.
constexpr int kLanes = TriangleIndex::kBatchLanes;
using VecF = float __attribute__((vector_size(4 * kLanes)));
using VecI = int __attribute__((vector_size(4 * kLanes)));

// ceil and floor through an integer conversion; |x| is kept below 1e9.
inline VecI ceilToInt(VecF x) {
  x = x < -1.0e9f ? VecF{} - 1.0e9f : x;
  x = x > 1.0e9f ? VecF{} + 1.0e9f : x;
  const VecI i = __builtin_convertvector(x, VecI);
  return i - (x > __builtin_convertvector(i, VecF));  // true is -1
}

inline VecI floorToInt(VecF x) {
  x = x < -1.0e9f ? VecF{} - 1.0e9f : x;
  x = x > 1.0e9f ? VecF{} + 1.0e9f : x;
  const VecI i = __builtin_convertvector(x, VecI);
  return i + (x < __builtin_convertvector(i, VecF));
}

inline VecF vmin(VecF a, VecF b) { return a < b ? a : b; }
inline VecF vmax(VecF a, VecF b) { return a > b ? a : b; }

// Edge function of pixel centre (pu, pv) against the directed edge a -> b:
// (b - a) x (p - a) = du pv - dv pu - k, with du, dv, k taken from the lexicographically
// smaller end, so that the two triangles sharing an edge get the same value (up to an exact
// sign) bit for bit: no pixel centre falls through a crack. The sign (edge direction times
// the triangle's orientation, +-1, exact) is folded into du, dv, k so that inside is >= 0.
// The scalar path below uses the same float expressions.
struct EdgeV {
  VecF du, dv, k;
  EdgeV(VecF a_u, VecF a_v, VecF b_u, VecF b_v) {
    const VecI swap = (b_u < a_u) | ((b_u == a_u) & (b_v < a_v));
    const VecF au = swap ? b_u : a_u;
    const VecF av = swap ? b_v : a_v;
    du = (swap ? a_u : b_u) - au;
    dv = (swap ? a_v : b_v) - av;
    k = du * av - dv * au;
    const VecF sign = swap ? VecF{} - 1.0f : VecF{} + 1.0f;
    du *= sign;
    dv *= sign;
    k *= sign;
  }
  void orient(VecF sign) {
    du *= sign;
    dv *= sign;
    k *= sign;
  }
  VecF at(VecF pu, VecF pv) const { return du * pv - dv * pu - k; }
};

struct EdgeS {
  float du, dv, k;
  EdgeS(float a_u, float a_v, float b_u, float b_v) {
    const bool swap = b_u < a_u || (b_u == a_u && b_v < a_v);
    const float au = swap ? b_u : a_u;
    const float av = swap ? b_v : a_v;
    du = (swap ? a_u : b_u) - au;
    dv = (swap ? a_v : b_v) - av;
    k = du * av - dv * au;
    const float sign = swap ? -1.0f : 1.0f;
    du *= sign;
    dv *= sign;
    k *= sign;
  }
  void orient(float sign) {
    du *= sign;
    dv *= sign;
    k *= sign;
  }
  float at(float pu, float pv) const { return du * pv - dv * pu - k; }
};

struct Frame {
  int W, H;
  float near, far;
  float* z_buffer;
  // (u, v, z) = A (p_F - o_F) + (b_u, b_v, 0), A row-major.
  float A[9];
  float o[3];
  float b_u, b_v;
};

// One triangle whatever its size (vertices in pixel units and z_C).
void rasterizeOne(const Frame& f, float u0, float v0, float z0, float u1, float v1, float z1, float u2, float v2,
                  float z2) {
  const float z_lo = std::min(z0, std::min(z1, z2)), z_hi = std::max(z0, std::max(z1, z2));
  if (z_lo > f.near || z_hi < f.far) return;
  const int c0 = std::max(0, static_cast<int>(std::ceil(std::max(std::min(u0, std::min(u1, u2)), -1e9f))));
  const int c1 = std::min(f.W - 1, static_cast<int>(std::floor(std::min(std::max(u0, std::max(u1, u2)), 1e9f))));
  const int r0 = std::max(0, static_cast<int>(std::ceil(std::max(std::min(v0, std::min(v1, v2)), -1e9f))));
  const int r1 = std::min(f.H - 1, static_cast<int>(std::floor(std::min(std::max(v0, std::max(v1, v2)), 1e9f))));
  if (c0 > c1 || r0 > r1) return;
  EdgeS e0(u1, v1, u2, v2), e1(u2, v2, u0, v0), e2(u0, v0, u1, v1);
  const float area = e2.at(u2, v2);
  if (area == 0.0f) return;  // seen edge-on: the neighbouring faces cover its pixels
  const float orient = area > 0.0f ? 1.0f : -1.0f;
  e0.orient(orient);
  e1.orient(orient);
  e2.orient(orient);
  const float inv_area = 1.0f / (orient * area);
  for (int r = r0; r <= r1; ++r) {
    float* row = f.z_buffer + static_cast<std::size_t>(r) * f.W;
    for (int c = c0; c <= c1; ++c) {
      const auto pu = static_cast<float>(c), pv = static_cast<float>(r);
      const float w0 = e0.at(pu, pv), w1 = e1.at(pu, pv), w2 = e2.at(pu, pv);
      if (w0 < 0.0f || w1 < 0.0f || w2 < 0.0f) continue;
      // The weights sum to the area up to rounding; the clamp keeps z within the triangle's
      // range even when it is seen nearly edge-on.
      const float z = std::clamp((w0 * z0 + w1 * z1 + w2 * z2) * inv_area, z_lo, z_hi);
      if (z <= f.near && z > row[c]) row[c] = z;
    }
  }
}

// One batch of the index (corners in F). Triangles whose pixel box spans more than 2 x 2
// centres go to rasterizeOne.
__attribute__((target_clones("avx2", "default"))) void rasterizeBatch(const Frame& f, const float* batch) {
  VecF u[3], v[3], z[3];
  for (int corner = 0; corner < 3; ++corner) {
    VecF x, y, w;
    __builtin_memcpy(&x, batch + (3 * corner + 0) * kLanes, sizeof(VecF));
    __builtin_memcpy(&y, batch + (3 * corner + 1) * kLanes, sizeof(VecF));
    __builtin_memcpy(&w, batch + (3 * corner + 2) * kLanes, sizeof(VecF));
    x = x - f.o[0];
    y = y - f.o[1];
    w = w - f.o[2];
    u[corner] = f.A[0] * x + f.A[1] * y + f.A[2] * w + f.b_u;
    v[corner] = f.A[3] * x + f.A[4] * y + f.A[5] * w + f.b_v;
    z[corner] = f.A[6] * x + f.A[7] * y + f.A[8] * w;
  }
  const VecF u0 = u[0], v0 = v[0], z0 = z[0], u1 = u[1], v1 = v[1], z1 = z[1], u2 = u[2], v2 = v[2], z2 = z[2];

  const VecI c0 = ceilToInt(vmin(u0, vmin(u1, u2)));
  const VecI c1 = floorToInt(vmax(u0, vmax(u1, u2)));
  const VecI r0 = ceilToInt(vmin(v0, vmin(v1, v2)));
  const VecI r1 = floorToInt(vmax(v0, vmax(v1, v2)));
  const VecF z_lo = vmin(z0, vmin(z1, z2));
  const VecF z_hi = vmax(z0, vmax(z1, z2));
  const VecI live = (c0 <= c1) & (r0 <= r1) & (z_lo <= f.near) & (z_hi >= f.far) & (c1 >= 0) &
                    (r1 >= 0) & (c0 < f.W) & (r0 < f.H);
  const VecI big = live & ((c1 - c0 >= 2) | (r1 - r0 >= 2));
  // Lane loops run over arrays: subscripting vectors in a loop makes GCC spill them per lane.
  alignas(64) int lane_mask[kLanes];
  __builtin_memcpy(lane_mask, &big, sizeof(VecI));
  int any_big = 0;
  for (int k = 0; k < kLanes; ++k) any_big |= lane_mask[k];
  if (any_big) {
    alignas(64) float corner[9][kLanes];
    const VecF* corners[9] = {&u0, &v0, &z0, &u1, &v1, &z1, &u2, &v2, &z2};
    for (int i = 0; i < 9; ++i) __builtin_memcpy(corner[i], corners[i], sizeof(VecF));
    for (int k = 0; k < kLanes; ++k) {
      if (lane_mask[k]) {
        rasterizeOne(f, corner[0][k], corner[1][k], corner[2][k], corner[3][k], corner[4][k], corner[5][k], corner[6][k],
                     corner[7][k], corner[8][k]);
      }
    }
  }
  const VecI small = live & ~big;
  __builtin_memcpy(lane_mask, &small, sizeof(VecI));
  int any_small = 0;
  for (int k = 0; k < kLanes; ++k) any_small |= lane_mask[k];
  if (!any_small) return;

  EdgeV e0(u1, v1, u2, v2), e1(u2, v2, u0, v0), e2(u0, v0, u1, v1);
  const VecF area = e2.at(u2, v2);
  const VecF orient = area > 0.0f ? VecF{} + 1.0f : VecF{} - 1.0f;
  e0.orient(orient);
  e1.orient(orient);
  e2.orient(orient);
  const VecI valid = small & (area != 0.0f);
  const VecF inv_area = 1.0f / (area != 0.0f ? orient * area : VecF{} + 1.0f);
  // The (up to) 2 x 2 centres (c0 + dc, r0 + dr) of each box.
  alignas(64) int pixel[kLanes];
  alignas(64) float depth[kLanes];
  for (int dr = 0; dr < 2; ++dr) {
    for (int dc = 0; dc < 2; ++dc) {
      const VecI c = c0 + dc, r = r0 + dr;
      const VecF pu = __builtin_convertvector(c, VecF), pv = __builtin_convertvector(r, VecF);
      const VecF w0 = e0.at(pu, pv), w1 = e1.at(pu, pv), w2 = e2.at(pu, pv);
      const VecF z = vmax(z_lo, vmin((w0 * z0 + w1 * z1 + w2 * z2) * inv_area, z_hi));
      const VecI in = valid & (c <= c1) & (r <= r1) & (c >= 0) & (r >= 0) & (c < f.W) & (r < f.H) & (w0 >= 0.0f) &
                      (w1 >= 0.0f) & (w2 >= 0.0f) & (z <= f.near);
      __builtin_memcpy(lane_mask, &in, sizeof(VecI));
      int any_in = 0;
      for (int k = 0; k < kLanes; ++k) any_in |= lane_mask[k];
      if (!any_in) continue;
      const VecI index = r * f.W + c;
      __builtin_memcpy(pixel, &index, sizeof(VecI));
      __builtin_memcpy(depth, &z, sizeof(VecF));
      for (int k = 0; k < kLanes; ++k) {
        if (!lane_mask[k]) continue;
        float& px = f.z_buffer[pixel[k]];
        if (depth[k] > px) px = depth[k];
      }
    }
  }
}

}  // namespace

void rasterizeDepth(const TriangleIndex& index, const Pose& T_CF, const DepthCameraParams& camera,
                    const std::vector<char>& slot_excluded, std::vector<float>& z_buffer) {
  const int W = camera.width_px;
  const int H = camera.height_px;
  const double s = camera.pixel_size_m;
  Frame frame{};
  frame.W = W;
  frame.H = H;
  frame.near = static_cast<float>(camera.near_m);
  frame.far = static_cast<float>(camera.far_m);
  frame.z_buffer = z_buffer.data();

  // p_F -> (u, v, z) = A (p_F - o_F) + b with o_F the camera origin in F: u = x_C / s + W/2 - 0.5
  // (column of a centre), v = -y_C / s + H/2 - 0.5. Subtracting o_F first keeps float
  // arithmetic accurate far from F's origin.
  Eigen::Matrix3d A = T_CF.linear();
  A.row(0) /= s;
  A.row(1) /= -s;
  const Eigen::Vector3d o_F = -(T_CF.linear().transpose() * T_CF.translation());
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) frame.A[3 * row + col] = static_cast<float>(A(row, col));
    frame.o[row] = static_cast<float>(o_F(row));
  }
  frame.b_u = static_cast<float>(0.5 * W - 0.5);
  frame.b_v = static_cast<float>(0.5 * H - 0.5);

  index.forEachLeafInView(T_CF.linear(), T_CF.translation(), 0.5 * W * s, 0.5 * H * s, camera.far_m, camera.near_m,
                          [&](const TriangleIndex::Leaf& leaf) {
                            if (!slot_excluded.empty() && slot_excluded[leaf.slot]) return;
                            for (std::uint32_t b = leaf.first_batch; b < leaf.first_batch + leaf.batch_count; ++b) {
                              rasterizeBatch(frame, index.batchData_F(b));
                            }
                          });
}

}  // namespace climbsim::scene
