#include "render_scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

#include "climbsim/errors.hpp"
#include "depth_rasterizer.hpp"
#include "embree_scene.hpp"
#include "triangle_index.hpp"

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

  const TriangleIndex& staticIndex() {
    if (!static_index) {
      static_index.emplace(*pending_static_mesh, static_slots);
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
  m.embree.emplace(static_mesh_W, m.static_slots, options.embree_device_config);
  if (options.depth_backend == DepthBackend::kRasterizer) {
    m.static_index.emplace(static_mesh_W, m.static_slots);
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
  body.embree_body = m.embree->addBody(mesh_B, slots, T_W_B);
  m.bodies.push_back(std::move(body));
  return m.bodies.size() - 1;
}

void RenderScene::setBodyPose(BodyId body, const Pose& T_W_B) {
  Impl& m = *impl_;
  requireFinite(T_W_B, "moving body pose");
  Impl::Body& b = m.bodies.at(body);
  b.T_W_B = T_W_B;
  m.embree->setBodyPose(b.embree_body, T_W_B);
}

void RenderScene::renderDepth(const Pose& T_W_C, const DepthCameraParams& camera,
                              const std::vector<std::uint32_t>& excluded_part_ids, DepthBackend backend,
                              DepthImage& image) {
  Impl& m = *impl_;
  camera.validate();
  requireFinite(T_W_C, "depth camera pose");
  m.markExcluded(excluded_part_ids);
  const std::size_t pixels = static_cast<std::size_t>(camera.width_px) * camera.height_px;
  const PixelTile& tile = camera.tile;
  if (!tile.whole() && backend != DepthBackend::kRasterizer) {
    throw ConfigError("depth camera: a tile needs the rasterizer backend, not embree");
  }
  if (tile.whole()) {
    m.z_buffer.assign(pixels, -std::numeric_limits<float>::infinity());
  } else {
    // Only the tile's rows are read back; the rasteriser writes nothing outside the tile (nor
    // outside its mask: there the tile keeps -inf, read back as far).
    m.z_buffer.resize(pixels);
    std::fill(m.z_buffer.begin() + static_cast<std::ptrdiff_t>(tile.row0) * camera.width_px,
              m.z_buffer.begin() + static_cast<std::ptrdiff_t>(tile.row0 + tile.rows) * camera.width_px,
              -std::numeric_limits<float>::infinity());
  }

  m.counters = RasterCounters{};
  if (backend == DepthBackend::kRasterizer) {
    const Pose T_C_W = T_W_C.inverse();
    rasterizeDepth(m.staticIndex(), T_C_W, camera, m.slot_excluded, m.z_buffer, m.options.raster_kernel, &m.counters);
    for (const Impl::Body& body : m.bodies) {
      rasterizeDepth(body.index, T_C_W * body.T_W_B, camera, m.slot_excluded, m.z_buffer, m.options.raster_kernel,
                     &m.counters);
    }
  } else {
    m.embree->renderDepth(T_W_C, camera, m.slot_excluded, m.z_buffer);
  }

  image.width_px = camera.width_px;
  image.height_px = camera.height_px;
  image.pixel_size_m = camera.pixel_size_m;
  image.near_m = camera.near_m;
  image.far_m = camera.far_m;
  image.quantised_8bit = false;
  image.headroom_m = 0.0;
  image.tile = tile;
  const auto far = static_cast<float>(camera.far_m);
  if (tile.whole()) {
    image.height_m.resize(pixels);
    for (std::size_t i = 0; i < pixels; ++i) image.height_m[i] = std::max(m.z_buffer[i], far);
  } else {
    image.height_m.resize(static_cast<std::size_t>(tile.rows) * tile.cols);
    for (int r = 0; r < tile.rows; ++r) {
      const float* row = m.z_buffer.data() + static_cast<std::size_t>(tile.row0 + r) * camera.width_px + tile.col0;
      float* out = image.height_m.data() + static_cast<std::size_t>(r) * tile.cols;
      for (int c = 0; c < tile.cols; ++c) out[c] = std::max(row[c], far);
    }
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
  m.embree->scan(T_W_S, laser, m.slot_excluded, scan.ranges_m);
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
