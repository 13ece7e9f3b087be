#include "render_scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

#include "climbsim/errors.hpp"
#include "area_sampling.hpp"
#include "depth_rasterizer.hpp"
#include "embree_scene.hpp"
#include "triangle_index.hpp"
#include "triangle_index_cache.hpp"

namespace climbsim::scene {

namespace {

void validateMesh(const TriangleMesh& mesh, const char* what) {
  if (mesh.part_ids.size() != mesh.triangles.size()) {
    std::ostringstream msg;
    msg << "render: " << what << ": " << mesh.part_ids.size() << " part ids for " << mesh.triangles.size()
        << " triangles (one per triangle expected)";
    throw ConfigError(msg.str());
  }
  for (std::size_t v = 0; v < mesh.vertices_m.size(); ++v) {
    if (!mesh.vertices_m[v].allFinite()) {
      std::ostringstream msg;
      msg << "render: " << what << ": vertex " << v << " = (" << mesh.vertices_m[v].transpose() << ") is not finite";
      throw ConfigError(msg.str());
    }
  }
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (const std::uint32_t v : mesh.triangles[t]) {
      if (v >= mesh.vertices_m.size()) {
        std::ostringstream msg;
        msg << "render: " << what << ": triangle " << t << " refers to vertex " << v << ", the mesh has "
            << mesh.vertices_m.size() << " vertices";
        throw ConfigError(msg.str());
      }
    }
  }
}

void requireFinite(const Pose& pose, const char* what) {
  if (!pose.matrix().allFinite()) throw std::invalid_argument(std::string("render: ") + what + " is not finite");
}

}  // namespace

struct RenderScene::Impl {
  RenderOptions options;
  std::unordered_map<std::uint32_t, std::uint32_t> slot_of_part;
  std::size_t static_triangles = 0;

  std::optional<EmbreeScene> embree;
  std::optional<TriangleIndex> static_index;
  // Kept only while the rasteriser's index of the static mesh has not been built.
  std::optional<TriangleMesh> pending_static_mesh;
  std::vector<std::uint32_t> static_slots;

  struct Body {
    TriangleIndex index;
    Pose T_W_B;
    std::vector<std::uint32_t> slots;  // distinct slots of the body
    std::size_t embree_body = 0;
  };
  std::vector<Body> bodies;

  std::vector<char> slot_excluded;
  std::vector<float> z_buffer;
  std::vector<float> centre;       // centre heights (at least far) of the last area-weighted frame
  std::vector<double> samples;  // per edge pixel e and sample k: its height at e * n + k (at least far)
  EdgeSampleBuffer edge_samples;      // the sample passes' values at the edge pixels
  std::vector<Pose> sample_cameras, body_cameras;  // T_C_W of each sample's camera, T_C_B of a body's
  std::vector<std::uint8_t> support_bounded;  // W * H: 1 where a support bound was given this frame
  std::vector<double> support_highest;        // W * H: the highest bound given (where bounded)
  // Tiles' masks and their dilations by 0, 1, 2 ... pixels (renderAreaWeighted).
  static constexpr std::size_t kDilatedMasksKept = 32;
  std::map<const PixelMask*, std::vector<std::shared_ptr<const PixelMask>>> dilated;
  RasterCounters counters;  // of the last depth frame

  std::vector<std::uint32_t> slotsOf(const TriangleMesh& mesh) {
    std::vector<std::uint32_t> slots(mesh.part_ids.size());
    for (std::size_t t = 0; t < slots.size(); ++t) {
      const auto [it, inserted] =
          slot_of_part.emplace(mesh.part_ids[t], static_cast<std::uint32_t>(slot_of_part.size()));
      slots[t] = it->second;
    }
    return slots;
  }

  void markExcluded(const std::vector<std::uint32_t>& excluded_part_ids) {
    slot_excluded.assign(slot_of_part.size(), 0);
    for (const std::uint32_t id : excluded_part_ids) {
      const auto it = slot_of_part.find(id);
      if (it != slot_of_part.end()) slot_excluded[it->second] = 1;
    }
  }

  /// One ray per pixel centre of camera T_W_C into z_buffer (-inf where nothing is met; a
  /// tile's rows only, the rest of the buffer as it was). On the rasteriser a `floor` above
  /// -inf (far) gives each pixel max(its height, floor) bit for bit, as the z-buffer is raised
  /// only by a greater value: the first of the highest values written stays either way.
  void renderPass(const Pose& T_W_C, const DepthCameraParams& camera, DepthBackend backend,
                  float floor = -std::numeric_limits<float>::infinity()) {
    const std::size_t pixels = static_cast<std::size_t>(camera.width_px) * camera.height_px;
    const PixelTile& tile = camera.tile;
    if (tile.whole()) {
      z_buffer.assign(pixels, floor);
    } else {
      // Only the tile's rows are read back; the rasteriser writes nothing outside the tile (nor
      // outside its mask: there the tile keeps the floor, read back as far).
      z_buffer.resize(pixels);
      std::fill(z_buffer.begin() + static_cast<std::ptrdiff_t>(tile.row0) * camera.width_px,
                z_buffer.begin() + static_cast<std::ptrdiff_t>(tile.row0 + tile.rows) * camera.width_px, floor);
    }
    if (backend == DepthBackend::kRasterizer) {
      const Pose T_C_W = T_W_C.inverse();
      rasterizeDepth(staticIndex(), T_C_W, camera, slot_excluded, z_buffer, options.raster_kernel, &counters,
                     options.reference_raster);
      for (const Body& body : bodies) {
        rasterizeDepth(body.index, T_C_W * body.T_W_B, camera, slot_excluded, z_buffer, options.raster_kernel,
                       &counters, options.reference_raster);
      }
    } else {
      embreeScene("the Embree depth backend").renderDepth(T_W_C, camera, slot_excluded, z_buffer);
    }
  }

  /// `tile` grown by `ring` pixels on each side (within the image), its mask dilated as often.
  PixelTile grownTile(const PixelTile& tile, int ring, int W, int H) {
    if (tile.whole() || ring == 0) return tile;
    PixelTile grown = tile;
    grown.row0 = std::max(0, tile.row0 - ring);
    grown.col0 = std::max(0, tile.col0 - ring);
    grown.rows = std::min(H, tile.row0 + tile.rows + ring) - grown.row0;
    grown.cols = std::min(W, tile.col0 + tile.cols + ring) - grown.col0;
    if (tile.mask) {
      // Each mask's dilations once (a shard's renderer cycles through a few masks); the map
      // holds the masks themselves, so no key's address is reused while it is in the map.
      auto found = dilated.find(tile.mask.get());
      if (found == dilated.end()) {
        if (dilated.size() >= kDilatedMasksKept) dilated.clear();
        found = dilated.emplace(tile.mask.get(), std::vector<std::shared_ptr<const PixelMask>>{tile.mask}).first;
      }
      auto& dilations = found->second;
      while (static_cast<int>(dilations.size()) <= ring) dilations.push_back(dilatedMask(*dilations.back()));
      grown.mask = dilations[static_cast<std::size_t>(ring)];
    }
    return grown;
  }

  /// DepthCameraParams::samples_per_pixel > 1: the centre rays of the image's pixels and their
  /// neighbours (a tile grown by one pixel, its mask dilated), then for the edge pixels among
  /// the image's (area_sampling.hpp) the mean of samples_per_pixel rays over their square, the
  /// other pixels their centre's height. Each sample pass moves the camera by one point's
  /// offset within the pixel (x along +column, y against +row), so that its pixel (r, c) holds
  /// the ray through that point of pixel (r, c); a pixel's sum runs over the passes in pattern
  /// order. With support heights (DepthCameraParams::support_slope > 0) the edge pixels next to
  /// the image's are sampled too (centres of a tile grown by two pixels), as each edge pixel
  /// bounds its own and its 8 neighbours' supports. Every value read is the whole image's bit
  /// for bit, so a tile holds the whole image's pixels and supports.
  void renderAreaWeighted(const Pose& T_W_C, const DepthCameraParams& camera, DepthBackend backend, DepthImage& image) {
    const PixelTile& tile = camera.tile;
    const int W = camera.width_px, H = camera.height_px;
    const int row0 = tile.whole() ? 0 : tile.row0, col0 = tile.whole() ? 0 : tile.col0;
    const int rows = tile.whole() ? H : tile.rows, cols = tile.whole() ? W : tile.cols;
    const auto far = static_cast<float>(camera.far_m);
    const int ring = camera.support_slope > 0.0 ? 1 : 0;  // edge pixels sampled outside the tile
    DepthCameraParams pass = camera;
    pass.samples_per_pixel = 1;
    pass.tile = grownTile(tile, 1 + ring, W, H);
    if (backend == DepthBackend::kRasterizer && !options.reference_raster) {
      renderPass(T_W_C, pass, backend, far);  // the centre heights at least far as they are written
      centre.swap(z_buffer);
    } else {
      renderPass(T_W_C, pass, backend);
      centre.resize(z_buffer.size());
      for (int r = pass.tile.whole() ? 0 : pass.tile.row0; r < (pass.tile.whole() ? H : pass.tile.row0 + pass.tile.rows); ++r) {
        for (int c = 0; c < W; ++c) {
          const std::size_t i = static_cast<std::size_t>(r) * W + c;
          centre[i] = std::max(z_buffer[i], far);
        }
      }
    }
    const PixelMask* mask = tile.mask.get();
    const auto inTile = [&](int r, int c) {
      return r >= row0 && r < row0 + rows && c >= col0 && c < col0 + cols && (!mask || mask->contains(r, c));
    };
    if (!mask) {
      for (int r = 0; r < rows; ++r) {
        const float* in = centre.data() + static_cast<std::size_t>(row0 + r) * W + col0;
        std::copy(in, in + cols, image.height_m.data() + static_cast<std::size_t>(r) * cols);
      }
    } else {
      // far, and the centre heights along the mask's row runs within the tile.
      std::fill(image.height_m.begin(), image.height_m.end(), far);
      for (const PixelMask::Run& run : mask->runs()) {
        const int r = static_cast<int>(run.raster / static_cast<std::uint32_t>(W));
        const int c = static_cast<int>(run.raster % static_cast<std::uint32_t>(W));
        const int c0 = std::max(c, col0), c1 = std::min(c + static_cast<int>(run.length), col0 + cols);
        if (r < row0 || r >= row0 + rows || c0 >= c1) continue;
        const float* in = centre.data() + static_cast<std::size_t>(r) * W;
        std::copy(in + c0, in + c1, image.height_m.data() + static_cast<std::size_t>(r - row0) * cols + (c0 - col0));
      }
    }
    const PixelTile sampled = grownTile(tile, ring, W, H);
    const std::vector<std::uint32_t> edges = sampled.whole()
        ? edgePixels(centre, W, H, 0, 0, H, W, nullptr, kEdgeThreshold_m, options.reference_raster,
                     options.raster_kernel)
        : edgePixels(centre, W, H, sampled.row0, sampled.col0, sampled.rows, sampled.cols, sampled.mask.get(),
                     kEdgeThreshold_m, options.reference_raster, options.raster_kernel);
    if (edges.empty()) return;
    pass.tile = tileOf(W, H, edges);
    const int n = camera.samples_per_pixel;
    samples.assign(edges.size() * static_cast<std::size_t>(n), 0.0);
    const auto offsets = subpixelOffsets(n);
    const double s = camera.pixel_size_m;
    if (backend == DepthBackend::kRasterizer && !options.reference_raster) {
      samplePasses(T_W_C, pass, edges, offsets);
    } else {
      for (std::size_t k = 0; k < offsets.size(); ++k) {
        renderPass(T_W_C * Eigen::Translation3d(offsets[k].first * s, -offsets[k].second * s, 0.0), pass, backend);
        keepSamples(edges, far, k, offsets.size());
      }
    }
    const auto valueAt = [&](int r, int c) -> float& {
      return image.height_m[static_cast<std::size_t>(r - row0) * cols + (c - col0)];
    };
    for (std::size_t e = 0; e < edges.size(); ++e) {
      const int r = static_cast<int>(edges[e] / static_cast<std::uint32_t>(W));
      const int c = static_cast<int>(edges[e] % static_cast<std::uint32_t>(W));
      if (!inTile(r, c)) continue;
      double sum = 0.0;
      for (int k = 0; k < n; ++k) sum += samples[e * n + k];
      valueAt(r, c) = std::max(static_cast<float>(sum / n), far);
    }
    if (ring == 0) return;
    // Supports: each edge pixel's bound for itself and its neighbours in the tile, the highest
    // per pixel, kept where it lies above the pixel's height (in raster order).
    const std::size_t pixels = static_cast<std::size_t>(W) * H;
    if (support_bounded.size() != pixels) {
      support_bounded.assign(pixels, 0);
      support_highest.resize(pixels);
    }
    std::size_t first = pixels, last = 0;  // the pixels bounded lie in first .. last - 1
    for (std::size_t e = 0; e < edges.size(); ++e) {
      const int r = static_cast<int>(edges[e] / static_cast<std::uint32_t>(W));
      const int c = static_cast<int>(edges[e] % static_cast<std::uint32_t>(W));
      // A bound never exceeds the highest sample (slope * distance >= 0): where that lies at or
      // below a neighbour's height, this pixel's bound can neither give the neighbour a support
      // nor be the highest of one that does, so it is not computed.
      const double* z = samples.data() + e * n;
      const float ceiling = std::max(static_cast<float>(*std::max_element(z, z + n)), far);
      std::optional<SupportBound> bound;
      for (int dr = -1; dr <= 1; ++dr) {
        for (int dc = -1; dc <= 1; ++dc) {
          if (r + dr < 0 || r + dr >= H || c + dc < 0 || c + dc >= W || !inTile(r + dr, c + dc)) continue;
          if (ceiling <= valueAt(r + dr, c + dc)) continue;
          if (!bound) bound.emplace(edgeNormal(centre, W, H, r, c), camera.support_slope, s);
          const double support = bound->at(z, static_cast<std::size_t>(n), offsets, {dc, dr});
          const std::size_t q = static_cast<std::size_t>(r + dr) * W + static_cast<std::size_t>(c + dc);
          if (support_bounded[q] == 0) {
            support_bounded[q] = 1;
            support_highest[q] = support;
            first = std::min(first, q);
            last = std::max(last, q + 1);
          } else if (support_highest[q] < support) {
            support_highest[q] = support;
          }
        }
      }
    }
    constexpr std::size_t kWord = sizeof(std::uint64_t);
    for (std::size_t q = first; q < last; ++q) {
      if (q % kWord == 0 && q + kWord <= last) {
        std::uint64_t word = 0;
        std::memcpy(&word, support_bounded.data() + q, kWord);
        if (word == 0) {
          q += kWord - 1;
          continue;
        }
      }
      if (support_bounded[q] == 0) continue;
      support_bounded[q] = 0;
      const auto support = std::max(static_cast<float>(support_highest[q]), far);
      if (support > valueAt(static_cast<int>(q / static_cast<std::size_t>(W)), static_cast<int>(q % static_cast<std::size_t>(W)))) {
        image.support_px.push_back(static_cast<std::uint32_t>(q));
        image.support_m.push_back(support);
      }
    }
  }

  /// Keeps sample k of `count` of the last pass's heights at the edge pixels (at least far).
  void keepSamples(const std::vector<std::uint32_t>& edges, float far, std::size_t k, std::size_t count) {
    for (std::size_t e = 0; e < edges.size(); ++e) {
      samples[e * count + k] = static_cast<double>(std::max(z_buffer[edges[e]], far));
    }
  }

  /// The sample passes of renderAreaWeighted on the rasteriser with one walk of each index:
  /// the batches that may write an edge pixel (`pass`'s tile and mask: the edge pixels) for
  /// any sample point (all within half a pixel of the centre) are found once, then every
  /// sample's camera draws them at once (rasterizeEdgeSamples: each sample's pass's values at
  /// the edge pixels, bit for bit), each triangle evaluated only at the edge pixels it may cover.
  void samplePasses(const Pose& T_W_C, const DepthCameraParams& pass, const std::vector<std::uint32_t>& edges,
                    const std::vector<std::pair<double, double>>& offsets) {
    const auto far = static_cast<float>(pass.far_m);
    const double s = pass.pixel_size_m;
    const Pose T_C_W = T_W_C.inverse();
    constexpr int kSampleMarginPx = 1;
    std::vector<std::vector<BatchRun>> runs;
    runs.push_back(batchesInView(staticIndex(), T_C_W, pass, slot_excluded, kSampleMarginPx, false, &counters));
    for (const Body& body : bodies) {
      runs.push_back(
          batchesInView(body.index, T_C_W * body.T_W_B, pass, slot_excluded, kSampleMarginPx, false, &counters));
    }
    const int n = static_cast<int>(offsets.size());
    edge_samples.start(edges, pass.width_px, pass.height_px, n);
    sample_cameras.resize(offsets.size());
    for (std::size_t k = 0; k < offsets.size(); ++k) {
      sample_cameras[k] = (T_W_C * Eigen::Translation3d(offsets[k].first * s, -offsets[k].second * s, 0.0)).inverse();
    }
    rasterizeEdgeSamples(staticIndex(), runs[0], sample_cameras, pass, edge_samples, options.raster_kernel, &counters);
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      body_cameras.resize(offsets.size());
      for (std::size_t k = 0; k < offsets.size(); ++k) body_cameras[k] = sample_cameras[k] * bodies[b].T_W_B;
      rasterizeEdgeSamples(bodies[b].index, runs[b + 1], body_cameras, pass, edge_samples, options.raster_kernel,
                           &counters);
    }
    for (std::size_t e = 0; e < edges.size(); ++e) {
      for (int k = 0; k < n; ++k) samples[e * n + k] = static_cast<double>(std::max(edge_samples.at(e, k), far));
    }
  }

  /// The Embree scene, which `what` needs; a renderer built without it refuses.
  EmbreeScene& embreeScene(const char* what) {
    if (!embree) throw std::logic_error(std::string("render: ") + what + " needs the Embree scene (RenderOptions::embree)");
    return *embree;
  }

  const TriangleIndex& staticIndex() {
    if (!static_index) {
      static_index.emplace(cachedTriangleIndex(*pending_static_mesh, static_slots, options.index_cache_dir));
      pending_static_mesh.reset();
      static_slots.clear();
      static_slots.shrink_to_fit();
    }
    return *static_index;
  }
};

RenderScene::RenderScene(const TriangleMesh& static_mesh_W, const RenderOptions& options)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  validateMesh(static_mesh_W, "static mesh");
  m.options = options;
  m.static_triangles = static_mesh_W.triangles.size();
  m.static_slots = m.slotsOf(static_mesh_W);
  if (options.embree) {
    m.embree.emplace(static_mesh_W, m.static_slots, options.embree_device_config);
  } else if (options.depth_backend == DepthBackend::kEmbree) {
    throw std::invalid_argument("render: the Embree depth backend needs RenderOptions::embree");
  }
  if (options.depth_backend == DepthBackend::kRasterizer) {
    m.static_index.emplace(cachedTriangleIndex(static_mesh_W, m.static_slots, options.index_cache_dir));
    m.static_slots.clear();
    m.static_slots.shrink_to_fit();
  } else {
    m.pending_static_mesh = static_mesh_W;
  }
}

RenderScene::~RenderScene() = default;
RenderScene::RenderScene(RenderScene&&) noexcept = default;
RenderScene& RenderScene::operator=(RenderScene&&) noexcept = default;

RenderScene::BodyId RenderScene::addBody(const TriangleMesh& mesh_B, const Pose& T_W_B) {
  Impl& m = *impl_;
  validateMesh(mesh_B, "moving body mesh");
  requireFinite(T_W_B, "moving body pose");
  Impl::Body body;
  const std::vector<std::uint32_t> slots = m.slotsOf(mesh_B);
  body.index = TriangleIndex(mesh_B, slots);
  body.T_W_B = T_W_B;
  body.slots = slots;
  std::sort(body.slots.begin(), body.slots.end());
  body.slots.erase(std::unique(body.slots.begin(), body.slots.end()), body.slots.end());
  if (m.embree) body.embree_body = m.embree->addBody(mesh_B, slots, T_W_B);
  m.bodies.push_back(std::move(body));
  return m.bodies.size() - 1;
}

void RenderScene::setBodyPose(BodyId body, const Pose& T_W_B) {
  Impl& m = *impl_;
  requireFinite(T_W_B, "moving body pose");
  Impl::Body& b = m.bodies.at(body);
  b.T_W_B = T_W_B;
  if (m.embree) m.embree->setBodyPose(b.embree_body, T_W_B);
}

void RenderScene::renderDepth(const Pose& T_W_C, const DepthCameraParams& camera,
                              const std::vector<std::uint32_t>& excluded_part_ids, DepthBackend backend,
                              DepthImage& image) {
  Impl& m = *impl_;
  camera.validate();
  requireFinite(T_W_C, "depth camera pose");
  m.markExcluded(excluded_part_ids);
  const PixelTile& tile = camera.tile;
  if (!tile.whole() && backend != DepthBackend::kRasterizer) {
    throw ConfigError("depth camera: a tile needs the rasterizer backend, not embree");
  }
  m.counters = RasterCounters{};

  image.width_px = camera.width_px;
  image.height_px = camera.height_px;
  image.pixel_size_m = camera.pixel_size_m;
  image.near_m = camera.near_m;
  image.far_m = camera.far_m;
  image.quantised_8bit = false;
  image.headroom_m = 0.0;
  image.tile = tile;
  const int rows = tile.whole() ? camera.height_px : tile.rows;
  const int cols = tile.whole() ? camera.width_px : tile.cols;
  const int row0 = tile.whole() ? 0 : tile.row0;
  const int col0 = tile.whole() ? 0 : tile.col0;
  image.height_m.resize(static_cast<std::size_t>(rows) * cols);
  image.support_px.clear();
  image.support_m.clear();
  const auto far = static_cast<float>(camera.far_m);
  // The image's pixel (row0 + r, col0 + c) of the last pass, at least far.
  const auto passHeight = [&](int r, int c) {
    return std::max(m.z_buffer[static_cast<std::size_t>(row0 + r) * camera.width_px + col0 + c], far);
  };
  const int n = camera.samples_per_pixel;
  if (n == 1) {
    m.renderPass(T_W_C, camera, backend);
    for (int r = 0; r < rows; ++r) {
      float* out = image.height_m.data() + static_cast<std::size_t>(r) * cols;
      for (int c = 0; c < cols; ++c) out[c] = passHeight(r, c);
    }
  } else {
    m.renderAreaWeighted(T_W_C, camera, backend, image);
  }
  if (camera.quantised_8bit) quantise8bit(image);
}

double RenderScene::depthHeightBound(const Pose& T_W_C, const DepthCameraParams& camera,
                                     const std::vector<std::uint32_t>& excluded_part_ids) {
  Impl& m = *impl_;
  camera.validate();
  requireFinite(T_W_C, "depth camera pose");
  m.markExcluded(excluded_part_ids);
  const Pose T_C_W = T_W_C.inverse();
  double top = depthTopBound(m.staticIndex(), T_C_W, camera, m.slot_excluded);
  for (const Impl::Body& body : m.bodies) {
    top = std::max(top, depthTopBound(body.index, T_C_W * body.T_W_B, camera, m.slot_excluded));
  }
  // The rasteriser computes z in float from vertices shifted by the camera origin: a few
  // 1e-7 m of rounding for a wall metres from the world origin; 10 µm cover it.
  constexpr double kFloatMargin_m = 1e-5;
  return std::clamp(top + kFloatMargin_m, camera.far_m, camera.near_m);
}

void RenderScene::renderDepth(const Pose& T_W_C, const DepthCameraParams& camera,
                              const std::vector<std::uint32_t>& excluded_part_ids, DepthImage& image) {
  renderDepth(T_W_C, camera, excluded_part_ids, impl_->options.depth_backend, image);
}

DepthImage RenderScene::renderDepth(const Pose& T_W_C, const DepthCameraParams& camera,
                                    const std::vector<std::uint32_t>& excluded_part_ids) {
  DepthImage image;
  renderDepth(T_W_C, camera, excluded_part_ids, image);
  return image;
}

void RenderScene::scanLaser(const Pose& T_W_S, const LaserParams& laser,
                            const std::vector<std::uint32_t>& excluded_part_ids, LaserScan& scan) {
  Impl& m = *impl_;
  laser.validate();
  requireFinite(T_W_S, "laser scanner pose");
  m.markExcluded(excluded_part_ids);
  scan.angle_min_rad = laser.angle_min_rad;
  scan.angle_increment_rad = laser.angle_increment_rad;
  scan.range_min_m = laser.range_min_m;
  scan.range_max_m = laser.range_max_m;
  scan.T_W_S = T_W_S;
  m.embreeScene("a laser scan").scan(T_W_S, laser, m.slot_excluded, scan.ranges_m);
}

LaserScan RenderScene::scanLaser(const Pose& T_W_S, const LaserParams& laser,
                                 const std::vector<std::uint32_t>& excluded_part_ids) {
  LaserScan scan;
  scanLaser(T_W_S, laser, excluded_part_ids, scan);
  return scan;
}

const RasterCounters& RenderScene::lastDepthCounters() const { return impl_->counters; }

std::size_t RenderScene::staticTriangleCount() const { return impl_->static_triangles; }

DepthBackend RenderScene::defaultDepthBackend() const { return impl_->options.depth_backend; }

}  // namespace climbsim::scene
