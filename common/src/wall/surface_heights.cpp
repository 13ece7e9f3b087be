#include "climbsim/wall/surface_heights.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "climbsim/wall/wall_coverage.hpp"

namespace climbsim::scene {
namespace {

constexpr float kNone = -std::numeric_limits<float>::infinity();
constexpr std::int64_t kBlocksPerTile = SurfaceHeights::kTileCells / SurfaceHeights::kBlockCells;
/// Blocks per row run: the search tests 4 neighbouring blocks of a row at once first.
constexpr std::int64_t kRunBlocks = 4;
constexpr std::int64_t kRunsPerTile = kBlocksPerTile / kRunBlocks;

std::int64_t floorDiv(std::int64_t a, std::int64_t b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

std::int64_t tileKey(std::int64_t ti, std::int64_t tj) {
  return static_cast<std::int64_t>((static_cast<std::uint64_t>(ti) << 32) ^ static_cast<std::uint32_t>(tj));
}

}  // namespace

/// Heights of kTileCells² grid points, row-major in j, the highest of each block's row of 4
/// points, of each 4 x 4 block, of each run of kRunBlocks blocks along a row of blocks, of each
/// row of blocks, and of the tile.
struct SurfaceHeights::Tile {
  std::vector<float> h = std::vector<float>(std::size_t(kTileCells) * kTileCells, kNone);
  std::vector<float> block_max = std::vector<float>(std::size_t(kBlocksPerTile) * kBlocksPerTile, kNone);
  std::vector<float> quad_max = std::vector<float>(std::size_t(kTileCells) * kBlocksPerTile, kNone);
  std::vector<float> run_max = std::vector<float>(std::size_t(kBlocksPerTile) * kRunsPerTile, kNone);
  std::vector<float> row_max = std::vector<float>(std::size_t(kBlocksPerTile), kNone);
  float top = kNone;
};

SurfaceHeights::SurfaceHeights(TriangleMesh mesh_W, double reach_m, double cell_m, double patch_m)
    : mesh_(std::move(mesh_W)), reach_m_(reach_m), cell_m_(cell_m) {
  if (!(reach_m >= 0.0) || !(cell_m > 0.0) || !(patch_m >= 0.0) || !(patch_m <= kTileCells * cell_m)) {
    throw std::invalid_argument("SurfaceHeights: reach >= 0, cell > 0 and patch in [0, 64 cells]");
  }
  patch_half_cells_ = static_cast<int>(std::lround(patch_m / (2.0 * cell_m)));
  const auto& v = mesh_.vertices_m;
  // Neighbouring triangles mostly fall in the same tile: its bucket is kept at hand (a map's
  // elements stay where they are when it grows).
  std::int64_t last_key = 0;
  std::vector<std::uint32_t>* last_bucket = nullptr;
  for (std::uint32_t k = 0; k < mesh_.triangles.size(); ++k) {
    const auto& t = mesh_.triangles[k];
    const Eigen::Vector3f &a = v[t[0]], &b = v[t[1]], &c = v[t[2]];
    if (std::max({a.z(), b.z(), c.z()}) < -reach_m) continue;
    const double lo_x = std::min({a.x(), b.x(), c.x()}), hi_x = std::max({a.x(), b.x(), c.x()});
    const double lo_y = std::min({a.y(), b.y(), c.y()}), hi_y = std::max({a.y(), b.y(), c.y()});
    if (!std::isfinite(lo_x + hi_x + lo_y + hi_y)) continue;
    const auto i0 = static_cast<std::int64_t>(std::ceil(lo_x / cell_m_)), i1 = static_cast<std::int64_t>(std::floor(hi_x / cell_m_));
    const auto j0 = static_cast<std::int64_t>(std::ceil(lo_y / cell_m_)), j1 = static_cast<std::int64_t>(std::floor(hi_y / cell_m_));
    if (i0 > i1 || j0 > j1) continue;
    for (std::int64_t tj = floorDiv(j0, kTileCells); tj <= floorDiv(j1, kTileCells); ++tj) {
      for (std::int64_t ti = floorDiv(i0, kTileCells); ti <= floorDiv(i1, kTileCells); ++ti) {
        const std::int64_t key = tileKey(ti, tj);
        if (!last_bucket || key != last_key) last_bucket = &buckets_[key], last_key = key;
        last_bucket->push_back(k);
      }
    }
  }
}

SurfaceHeights::~SurfaceHeights() = default;
SurfaceHeights::SurfaceHeights(SurfaceHeights&&) noexcept = default;
SurfaceHeights& SurfaceHeights::operator=(SurfaceHeights&&) noexcept = default;

std::vector<float> SurfaceHeights::sampled(std::int64_t i0, std::int64_t j0, std::int64_t n) const {
  std::vector<float> out(std::size_t(n * n), kNone);
  const std::int64_t i1 = i0 + n - 1, j1 = j0 + n - 1;
  for (std::int64_t tj = floorDiv(j0, kTileCells); tj <= floorDiv(j1, kTileCells); ++tj) {
    for (std::int64_t ti = floorDiv(i0, kTileCells); ti <= floorDiv(i1, kTileCells); ++ti) {
      const auto found = buckets_.find(tileKey(ti, tj));
      if (found == buckets_.end()) continue;
      // This tile's points of the square (a triangle in several tiles' buckets is met once per point).
      const std::int64_t ci0 = std::max(i0, ti * kTileCells), ci1 = std::min(i1, ti * kTileCells + kTileCells - 1);
      const std::int64_t cj0 = std::max(j0, tj * kTileCells), cj1 = std::min(j1, tj * kTileCells + kTileCells - 1);
      for (const std::uint32_t k : found->second) {
        const auto& t = mesh_.triangles[k];
        const Eigen::Vector3d a = mesh_.vertices_m[t[0]].cast<double>();
        const Eigen::Vector3d b = mesh_.vertices_m[t[1]].cast<double>();
        const Eigen::Vector3d c = mesh_.vertices_m[t[2]].cast<double>();
        // Barycentric coordinates in the wall plane; a triangle standing on edge is met by no line along z.
        const double det = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
        if (std::abs(det) < 1e-18) continue;
        const std::int64_t pi0 = std::max<std::int64_t>(ci0, std::ceil(std::min({a.x(), b.x(), c.x()}) / cell_m_));
        const std::int64_t pi1 = std::min<std::int64_t>(ci1, std::floor(std::max({a.x(), b.x(), c.x()}) / cell_m_));
        const std::int64_t pj0 = std::max<std::int64_t>(cj0, std::ceil(std::min({a.y(), b.y(), c.y()}) / cell_m_));
        const std::int64_t pj1 = std::min<std::int64_t>(cj1, std::floor(std::max({a.y(), b.y(), c.y()}) / cell_m_));
        for (std::int64_t j = pj0; j <= pj1; ++j) {
          const double y = double(j) * cell_m_;
          for (std::int64_t i = pi0; i <= pi1; ++i) {
            const double x = double(i) * cell_m_;
            const double u = ((x - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (y - a.y())) / det;
            const double w = ((b.x() - a.x()) * (y - a.y()) - (x - a.x()) * (b.y() - a.y())) / det;
            const double eps = 1e-9;
            if (u < -eps || w < -eps || u + w > 1.0 + eps) continue;
            const double z = a.z() + u * (b.z() - a.z()) + w * (c.z() - a.z());
            if (!(z >= -reach_m_)) continue;
            float& h = out[std::size_t(j - j0) * std::size_t(n) + std::size_t(i - i0)];
            h = std::max(h, static_cast<float>(z));
          }
        }
      }
    }
  }
  return out;
}

namespace {

/// The enveloped heights of the m x m points from (k, k) of the n x n sampled heights `s`
/// (n = m + 2k): over each point's (2k + 1)² neighbours with a surface, their value where they
/// are all equal, else their mean; kNone where none has a surface. Sums along rows, then
/// along columns, each sum over d = 0 .. 2k in that order; a point without a surface adds
/// +0.0 to a sum (never -0.0: it starts at +0.0), +inf to a least and -inf to a greatest value,
/// which leaves each unchanged, so the loops run over a whole row of points at once (and
/// vectorise).
/// std::min and std::max by value ((b < a) ? b : a and (a < b) ? b : a): selects the loops
/// can vectorise.
inline float least(float a, float b) { return b < a ? b : a; }
inline float greatest(float a, float b) { return a < b ? b : a; }
/// has ? h : +0.0f, by masking h's bits (a select GCC vectorises before a conversion to double).
inline float valueOrZero(float h, bool has) {
  std::uint32_t bits;
  std::memcpy(&bits, &h, sizeof bits);
  bits &= has ? 0xffffffffu : 0u;
  float v;
  std::memcpy(&v, &bits, sizeof v);
  return v;
}

std::vector<float> enveloped(const std::vector<float>& s, std::size_t n, std::size_t k) {
  const std::size_t m = n - 2 * k;
  constexpr float kInf = std::numeric_limits<float>::infinity();
  // Per point of the n rows x m columns: the sum, count, least and greatest along its row.
  std::vector<double> row_sum(n * m, 0.0);
  std::vector<std::int32_t> row_count(n * m, 0);
  std::vector<float> row_lo(n * m, kInf), row_hi(n * m, kNone);
  for (std::size_t j = 0; j < n; ++j) {
    double* __restrict sum = &row_sum[j * m];
    std::int32_t* __restrict count = &row_count[j * m];
    float* __restrict lo = &row_lo[j * m];
    float* __restrict hi = &row_hi[j * m];
    for (std::size_t d = 0; d <= 2 * k; ++d) {
      const float* __restrict in = &s[j * n + d];
      for (std::size_t i = 0; i < m; ++i) {
        const float h = in[i];
        const bool has = h != kNone;
        sum[i] += double(valueOrZero(h, has));
        count[i] += std::int32_t(has);
        lo[i] = least(lo[i], has ? h : kInf);
        hi[i] = greatest(hi[i], h);
      }
    }
  }
  std::vector<float> out(m * m, kNone);
  std::vector<double> sum(m);
  std::vector<std::int32_t> count(m);
  std::vector<float> lo(m), hi(m);
  for (std::size_t j = 0; j < m; ++j) {
    std::fill(sum.begin(), sum.end(), 0.0);
    std::fill(count.begin(), count.end(), 0);
    std::fill(lo.begin(), lo.end(), kInf);
    std::fill(hi.begin(), hi.end(), kNone);
    for (std::size_t d = 0; d <= 2 * k; ++d) {
      const std::size_t r = (j + d) * m;
      for (std::size_t i = 0; i < m; ++i) {
        sum[i] += row_sum[r + i];
        count[i] += row_count[r + i];
        lo[i] = least(lo[i], row_lo[r + i]);
        hi[i] = greatest(hi[i], row_hi[r + i]);
      }
    }
    for (std::size_t i = 0; i < m; ++i) {
      if (count[i] == 0) continue;
      out[j * m + i] = lo[i] == hi[i] ? lo[i] : static_cast<float>(sum[i] / double(count[i]));
    }
  }
  return out;
}

}  // namespace

SurfaceHeights::Tile SurfaceHeights::buildTile(std::int64_t ti, std::int64_t tj) const {
  Tile tile;
  const std::int64_t k = patch_half_cells_;
  if (k == 0) {
    tile.h = sampled(ti * kTileCells, tj * kTileCells, kTileCells);
  } else {
    tile.h = enveloped(sampled(ti * kTileCells - k, tj * kTileCells - k, kTileCells + 2 * k),
                       std::size_t(kTileCells + 2 * k), std::size_t(k));
  }
  for (int j = 0; j < kTileCells; ++j) {
    for (int i = 0; i < kTileCells; ++i) {
      float& m = tile.block_max[std::size_t(j / kBlockCells) * kBlocksPerTile + std::size_t(i / kBlockCells)];
      m = std::max(m, tile.h[std::size_t(j) * kTileCells + std::size_t(i)]);
      tile.top = std::max(tile.top, m);
      float& q = tile.quad_max[std::size_t(j) * kBlocksPerTile + std::size_t(i / kBlockCells)];
      q = std::max(q, tile.h[std::size_t(j) * kTileCells + std::size_t(i)]);
    }
  }
  for (std::size_t b = 0; b < tile.block_max.size(); ++b) {
    float& m = tile.run_max[b / kRunBlocks];
    m = std::max(m, tile.block_max[b]);
  }
  for (std::size_t b = 0; b < tile.block_max.size(); ++b) {
    float& m = tile.row_max[b / kBlocksPerTile];
    m = std::max(m, tile.block_max[b]);
  }
  return tile;
}

const SurfaceHeights::Tile& SurfaceHeights::tile(std::int64_t ti, std::int64_t tj) const {
  // The wheels' queries stay on a few tiles for thousands of steps: their slots first.
  const std::int64_t key = tileKey(ti, tj);
  const std::size_t slot_index = std::size_t(ti & (RecentTiles::kSide - 1)) * RecentTiles::kSide +
                                 std::size_t(tj & (RecentTiles::kSide - 1));
  if (recent_.tile[slot_index] && recent_.key[slot_index] == key) return *recent_.tile[slot_index];
  std::unique_ptr<Tile>& slot = tiles_[key];
  if (!slot) slot = std::make_unique<Tile>(buildTile(ti, tj));
  recent_.key[slot_index] = key, recent_.tile[slot_index] = slot.get();
  return *slot;
}

double SurfaceHeights::height(std::int64_t i, std::int64_t j) const {
  const std::int64_t ti = floorDiv(i, kTileCells), tj = floorDiv(j, kTileCells);
  return tile(ti, tj).h[std::size_t(j - tj * kTileCells) * kTileCells + std::size_t(i - ti * kTileCells)];
}

SphereRest SurfaceHeights::sphereRest(double x, double y, double r) const {
  SphereRest rest;
  double best = -std::numeric_limits<double>::infinity();
  if (!(std::isfinite(x) && std::isfinite(y) && r > 0.0)) return rest;
  const double inv = 1.0 / cell_m_;
  // height(i, j) with the tile of the last point at hand (the points asked for lie close together).
  const Tile* near_tile = nullptr;
  std::int64_t near_ti = 0, near_tj = 0;
  const auto heightAt = [&](std::int64_t i, std::int64_t j) -> double {
    const std::int64_t ti = floorDiv(i, kTileCells), tj = floorDiv(j, kTileCells);
    if (!near_tile || ti != near_ti || tj != near_tj) near_tile = &tile(ti, tj), near_ti = ti, near_tj = tj;
    return near_tile->h[std::size_t(j - tj * kTileCells) * kTileCells + std::size_t(i - ti * kTileCells)];
  };
  // The point straight below the centre, on the bilinear surface of its four grid points.
  {
    const double fx = x * inv, fy = y * inv;
    const auto i0 = static_cast<std::int64_t>(std::floor(fx)), j0 = static_cast<std::int64_t>(std::floor(fy));
    const double tx = fx - double(i0), ty = fy - double(j0);
    const double h00 = heightAt(i0, j0), h10 = heightAt(i0 + 1, j0), h01 = heightAt(i0, j0 + 1), h11 = heightAt(i0 + 1, j0 + 1);
    if (std::isfinite(h00) && std::isfinite(h10) && std::isfinite(h01) && std::isfinite(h11)) {
      const double h = (h00 * (1.0 - tx) + h10 * tx) * (1.0 - ty) + (h01 * (1.0 - tx) + h11 * tx) * ty;
      const double gx = ((h10 - h00) * (1.0 - ty) + (h11 - h01) * ty) * inv;
      const double gy = ((h01 - h00) * (1.0 - tx) + (h11 - h10) * tx) * inv;
      best = h + r;
      rest.touches = true;
      rest.point_m = Eigen::Vector3d(x, y, h);
      rest.level = gx == 0.0 && gy == 0.0;
      rest.normal = rest.level ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d(-gx, -gy, 1.0).normalized();
    }
  }
  // Every grid point within r that would hold the centre higher, block by block: a block whose
  // highest point at its nearest distance cannot beat the best so far is skipped. A point p
  // beats it when h_p >= best or r² - rho² > (best - h_p)² (no root unless it does); the same
  // test on the tiles' highest point narrows the square searched.
  const double r2 = r * r;
  const auto first_index = [&](double lo) { return static_cast<std::int64_t>(std::ceil(lo * inv)); };
  const auto last_index = [&](double hi) { return static_cast<std::int64_t>(std::floor(hi * inv)); };
  std::int64_t pi0 = first_index(x - r), pi1 = last_index(x + r), pj0 = first_index(y - r), pj1 = last_index(y + r);
  // The tiles under the footprint, looked up once.
  const std::int64_t ti0 = floorDiv(pi0, kTileCells), tj0 = floorDiv(pj0, kTileCells);
  const std::int64_t nti = floorDiv(pi1, kTileCells) - ti0 + 1, ntj = floorDiv(pj1, kTileCells) - tj0 + 1;
  std::array<const Tile*, 16> tiles{};
  const bool few = nti * ntj <= 16;
  if (few) {
    double top = -std::numeric_limits<double>::infinity();
    for (std::int64_t a = 0; a < ntj; ++a) {
      for (std::int64_t b = 0; b < nti; ++b) {
        const Tile* t = &tile(ti0 + b, tj0 + a);
        tiles[std::size_t(a * nti + b)] = t;
        top = std::max(top, double(t->top));
      }
    }
    const double gap = best - top;
    if (gap > 0.0) {
      const double reach2 = r2 - gap * gap;
      if (!(reach2 > 0.0)) {
        pi1 = pi0 - 1;  // no point can beat the best
      } else {
        const double reach = std::sqrt(reach2);
        pi0 = std::max(pi0, first_index(x - reach)), pi1 = std::min(pi1, last_index(x + reach));
        pj0 = std::max(pj0, first_index(y - reach)), pj1 = std::min(pj1, last_index(y + reach));
      }
    }
  }
  std::int64_t best_i = 0, best_j = 0;
  bool grid_point = false;
  const double block_m = kBlockCells * cell_m_;
  // A block is skipped when no point of it can beat the best (it lies outside the radius, or
  // its highest point at its nearest distance is too low). The blocks of a row within one tile,
  // and then each run of kRunBlocks of them, are skipped at once when the same test on their
  // highest point and their nearest distance says so: that distance is no larger and that point
  // no lower than any of their blocks', and the best only rises, so each block would be skipped
  // by its own test (the same points are searched in the same order).
  const std::int64_t bi_first = floorDiv(pi0, kBlockCells), bi_last = floorDiv(pi1, kBlockCells);
  /// True if the blocks b0 .. b1 of the row at distance dy, no higher than `top`, cannot beat the best.
  const auto skip = [&](std::int64_t b0, std::int64_t b1, double dy, float top) {
    const double lo_x = double(b0) * block_m, hi_x = double(b1) * block_m + (kBlockCells - 1) * cell_m_;
    const double dx = x < lo_x ? lo_x - x : (x > hi_x ? x - hi_x : 0.0);
    const double near2 = dx * dx + dy * dy;
    if (!(near2 < r2)) return true;
    const double gap = best - top;
    return gap > 0.0 && !(r2 - near2 > gap * gap);
  };
  const auto tileAt = [&](std::int64_t ti, std::int64_t tj) -> const Tile& {
    return few ? *tiles[std::size_t((tj - tj0) * nti + (ti - ti0))] : tile(ti, tj);
  };
  for (std::int64_t bj = floorDiv(pj0, kBlockCells); bj <= floorDiv(pj1, kBlockCells); ++bj) {
    const double lo_y = double(bj) * block_m, hi_y = lo_y + (kBlockCells - 1) * cell_m_;
    const double dy = y < lo_y ? lo_y - y : (y > hi_y ? y - hi_y : 0.0);
    const std::int64_t tj = floorDiv(bj, kBlocksPerTile);
    const std::int64_t lj = bj - tj * kBlocksPerTile;
    for (std::int64_t run = floorDiv(bi_first, kRunBlocks); run <= floorDiv(bi_last, kRunBlocks); ++run) {
      const std::int64_t b0 = std::max(bi_first, run * kRunBlocks), b1 = std::min(bi_last, run * kRunBlocks + kRunBlocks - 1);
      const std::int64_t ti = floorDiv(b0, kBlocksPerTile);
      const Tile* t = nullptr;
      if (run == floorDiv(bi_first, kRunBlocks) || b0 == ti * kBlocksPerTile) {
        // The first run of this row in this tile: the row's blocks in the tile first.
        const std::int64_t s1 = std::min(bi_last, ti * kBlocksPerTile + kBlocksPerTile - 1);
        if (s1 > b1) {
          t = &tileAt(ti, tj);
          if (skip(b0, s1, dy, t->row_max[std::size_t(lj)])) {
            run = floorDiv(s1, kRunBlocks);
            continue;
          }
        }
      }
      if (b1 > b0) {
        if (!t) t = &tileAt(ti, tj);
        if (skip(b0, b1, dy, t->run_max[std::size_t(lj) * kRunsPerTile + std::size_t(run - ti * kRunsPerTile)])) continue;
      }
      for (std::int64_t bi = b0; bi <= b1; ++bi) {
        const double lo_x = double(bi) * block_m, hi_x = lo_x + (kBlockCells - 1) * cell_m_;
        const double dx = x < lo_x ? lo_x - x : (x > hi_x ? x - hi_x : 0.0);
        const double near2 = dx * dx + dy * dy;
        if (!(near2 < r2)) continue;
        if (!t) t = &tileAt(ti, tj);
        const std::int64_t li = bi - ti * kBlocksPerTile;
        const double top_gap = best - t->block_max[std::size_t(lj) * kBlocksPerTile + std::size_t(li)];
        if (top_gap > 0.0 && !(r2 - near2 > top_gap * top_gap)) continue;
        const std::int64_t i0 = bi * kBlockCells, i1 = i0 + kBlockCells - 1;
        for (std::int64_t j = bj * kBlockCells; j < (bj + 1) * kBlockCells; ++j) {
          const double py = double(j) * cell_m_ - y;
          // The block's row of 4 points at once, by the same bound (a point's |px| is no
          // smaller than the row's nearest dx, its height no larger than the row's highest).
          const double lo_px = double(i0) * cell_m_, hi_px = double(i1) * cell_m_;
          const double row_dx = x < lo_px ? lo_px - x : (x > hi_px ? x - hi_px : 0.0);
          const double row_room = r2 - (row_dx * row_dx + py * py);
          if (!(row_room > 0.0)) continue;
          const double row_gap = best - t->quad_max[std::size_t(j - tj * kTileCells) * kBlocksPerTile + std::size_t(li)];
          if (row_gap > 0.0 && !(row_room > row_gap * row_gap)) continue;
          const float* row = &t->h[std::size_t(j - tj * kTileCells) * kTileCells];
          for (std::int64_t i = i0; i <= i1; ++i) {
            const double px = double(i) * cell_m_ - x;
            const double room = r2 - (px * px + py * py);
            if (!(room > 0.0)) continue;
            const double h = row[i - ti * kTileCells];
            const double gap = best - h;
            if (gap > 0.0 && !(room > gap * gap)) continue;
            const double z = h + std::sqrt(room);
            if (z > best) {
              best = z;
              best_i = i, best_j = j;
              grid_point = true;
            }
          }
        }
      }
    }
  }
  if (grid_point) {
    // Between the grid points: a parabola through the winner and its two neighbours along x,
    // and along y, puts the contact where the sampled surface's maximum lies, so that it moves
    // on smoothly from one grid point to the next as the wheel rolls. A neighbour without a
    // surface, outside the radius or across an edge (steeper than 1:1 from the winner) leaves
    // that axis at the grid point: an edge is a corner, not a curve.
    const double h_best = heightAt(best_i, best_j);
    const auto value = [&](std::int64_t i, std::int64_t j) {
      const double px = double(i) * cell_m_ - x, py = double(j) * cell_m_ - y;
      const double room = r2 - (px * px + py * py);
      const double h = room > 0.0 ? heightAt(i, j) : -std::numeric_limits<double>::infinity();
      if (!(std::fabs(h - h_best) <= cell_m_)) return -std::numeric_limits<double>::infinity();
      return h + std::sqrt(room);
    };
    const auto vertex = [&](double before, double after, double& rise) {
      const double curvature = before - 2.0 * best + after;
      if (!(std::isfinite(before) && std::isfinite(after) && curvature < 0.0)) return 0.0;
      const double offset = std::clamp(0.5 * (before - after) / curvature, -0.5, 0.5);
      rise -= 0.25 * (before - after) * offset;
      return offset;
    };
    double rise = 0.0;
    const double ox = vertex(value(best_i - 1, best_j), value(best_i + 1, best_j), rise);
    const double oy = vertex(value(best_i, best_j - 1), value(best_i, best_j + 1), rise);
    best += rise;
    const double px = (double(best_i) + ox) * cell_m_, py = (double(best_j) + oy) * cell_m_;
    const double room = std::max(0.0, r2 - ((px - x) * (px - x) + (py - y) * (py - y)));
    const Eigen::Vector3d p(px, py, best - std::sqrt(room));
    rest.touches = true;
    rest.level = false;
    rest.point_m = p;
    rest.normal = (Eigen::Vector3d(x, y, best) - p) / r;
  }
  if (rest.touches) rest.centre_z_m = best;
  return rest;
}

SurfaceHeights surfaceHeights(const Scene& scene, const std::string& pose_element, double reach_m, double cell_m,
                              double patch_m) {
  const std::size_t wall = wallPartOf(scene, pose_element);
  const Pose T_W_world = scene.worldPose(wall).inverse();
  TriangleMesh mesh_W;
  const auto& parts = scene.parts();
  for (std::size_t part = 0; part < parts.size(); ++part) {
    if (parts[part].mesh < 0 || scene.moving(part) || !scene.visible(part)) continue;
    // T_W_part along the tree when the part lies below the wall part, else through the world.
    Pose T = scene.localPose(part);
    int up = parts[part].parent;
    for (; up >= 0 && static_cast<std::size_t>(up) != wall; up = parts[up].parent) T = scene.localPose(up) * T;
    if (up < 0) T = T_W_world * scene.worldPose(part);
    const bool identity = T.matrix() == Eigen::Matrix4d::Identity();
    const LocalMesh& mesh = scene.description().meshes[parts[part].mesh];
    const auto base = static_cast<std::uint32_t>(mesh_W.vertices_m.size());
    const Eigen::Isometry3f Tf = T.cast<float>();
    for (const auto& v : mesh.vertices_m) mesh_W.vertices_m.push_back(identity ? v : Eigen::Vector3f(Tf * v));
    for (const auto& t : mesh.triangles) {
      mesh_W.triangles.push_back({base + t[0], base + t[1], base + t[2]});
      mesh_W.part_ids.push_back(static_cast<std::uint32_t>(part));
    }
  }
  return SurfaceHeights(std::move(mesh_W), reach_m, cell_m, patch_m);
}

}  // namespace climbsim::scene
