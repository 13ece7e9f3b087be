#include "embree_scene.hpp"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace climbsim::scene {

namespace {

constexpr int kPacket = 16;
constexpr unsigned kInvalid = RTC_INVALID_GEOMETRY_ID;

// Embree calls this from inside its functions; the error is reported after the call returns.
void recordError(void* user, RTCError code, const char* message) {
  auto* last = static_cast<std::string*>(user);
  if (last->empty()) last->assign("Embree error " + std::to_string(static_cast<int>(code)) + ": " + (message ? message : ""));
}

// Intersection context carrying the parts to leave out; Embree hands the pointer back to the
// filter, so the context must be the first member.
struct ExclusionContext {
  RTCIntersectContext context;
  const char* slot_excluded;
  const std::uint32_t* geom_slot;
};

void rejectExcluded(const RTCFilterFunctionNArguments* args) {
  const auto* ctx = reinterpret_cast<const ExclusionContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    if (ctx->slot_excluded[ctx->geom_slot[RTCHitN_geomID(args->hit, args->N, i)]]) args->valid[i] = 0;
  }
}

// One triangle geometry per slot from the triangles of `mesh` (vertices copied per slot).
// Returns the slot of every geometry, in geometry-id order.
std::vector<std::uint32_t> attachBySlot(RTCDevice device, RTCScene scene, const TriangleMesh& mesh,
                                        const std::vector<std::uint32_t>& slot_of_triangle) {
  std::vector<std::uint32_t> slots(slot_of_triangle);
  std::sort(slots.begin(), slots.end());
  slots.erase(std::unique(slots.begin(), slots.end()), slots.end());
  std::vector<std::uint32_t> geom_slot;
  std::vector<std::uint32_t> local_of(mesh.vertices_m.size(), UINT32_MAX);
  std::vector<std::uint32_t> used;
  std::vector<std::uint32_t> tris;
  for (const std::uint32_t slot : slots) {
    used.clear();
    tris.clear();
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      if (slot_of_triangle[t] != slot) continue;
      for (const std::uint32_t v : mesh.triangles[t]) {
        if (local_of[v] == UINT32_MAX) {
          local_of[v] = static_cast<std::uint32_t>(used.size());
          used.push_back(v);
        }
        tris.push_back(local_of[v]);
      }
    }
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vb = static_cast<float*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), used.size()));
    auto* ib = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), tris.size() / 3));
    if (vb == nullptr || ib == nullptr) {
      rtcReleaseGeometry(geom);
      throw std::runtime_error("Embree: cannot allocate the geometry buffers");
    }
    for (std::size_t k = 0; k < used.size(); ++k) {
      const Eigen::Vector3f& p = mesh.vertices_m[used[k]];
      vb[3 * k] = p.x();
      vb[3 * k + 1] = p.y();
      vb[3 * k + 2] = p.z();
      local_of[used[k]] = UINT32_MAX;
    }
    std::copy(tris.begin(), tris.end(), ib);
    rtcCommitGeometry(geom);
    const unsigned id = rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
    if (id >= geom_slot.size()) geom_slot.resize(id + 1, 0);
    geom_slot[id] = slot;
  }
  return geom_slot;
}

void setTransform(RTCGeometry instance, const Pose& T_W_B) {
  float xfm[12];
  for (int col = 0; col < 3; ++col) {
    for (int row = 0; row < 3; ++row) xfm[3 * col + row] = static_cast<float>(T_W_B.linear()(row, col));
  }
  for (int row = 0; row < 3; ++row) xfm[9 + row] = static_cast<float>(T_W_B.translation()(row));
  rtcSetGeometryTransform(instance, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm);
  rtcCommitGeometry(instance);
}

/// Lane k of a 16-ray packet: origin and direction (world frame), the hit interval
/// [tnear, tfar] along the direction, no hit yet.
void setRay(RTCRayHit16& packet, int k, const Eigen::Vector3f& origin, const Eigen::Vector3f& direction, float tnear,
            float tfar) {
  packet.ray.org_x[k] = origin.x();
  packet.ray.org_y[k] = origin.y();
  packet.ray.org_z[k] = origin.z();
  packet.ray.dir_x[k] = direction.x();
  packet.ray.dir_y[k] = direction.y();
  packet.ray.dir_z[k] = direction.z();
  packet.ray.tnear[k] = tnear;
  packet.ray.tfar[k] = tfar;
  packet.ray.time[k] = 0.0f;
  packet.ray.mask[k] = 0xFFFFFFFFu;
  packet.ray.id[k] = static_cast<unsigned>(k);
  packet.ray.flags[k] = 0;
  packet.hit.geomID[k] = kInvalid;
  packet.hit.instID[0][k] = kInvalid;
}

}  // namespace

struct EmbreeScene::Impl {
  std::string error;
  RTCDevice device = nullptr;
  RTCScene static_scene = nullptr;
  std::vector<std::uint32_t> static_geom_slot;
  RTCScene dynamic_scene = nullptr;  // instances of body parts

  struct Instance {
    RTCScene part_scene = nullptr;
    RTCGeometry instance = nullptr;
    std::uint32_t slot = 0;
    bool enabled = true;
  };
  struct Body {
    std::vector<Instance> instances;
  };
  std::vector<Body> bodies;
  bool dynamic_dirty = false;

  void check(const char* what) {
    if (!error.empty()) {
      const std::string message = std::string(what) + ": " + error;
      error.clear();
      throw std::runtime_error(message);
    }
  }

  // Enables exactly the body instances whose slot is not excluded, commits if anything
  // changed; returns whether any instance is enabled.
  bool prepareDynamic(const std::vector<char>& slot_excluded) {
    bool any = false;
    for (Body& body : bodies) {
      for (Instance& inst : body.instances) {
        const bool want = slot_excluded.empty() || !slot_excluded[inst.slot];
        if (want != inst.enabled) {
          want ? rtcEnableGeometry(inst.instance) : rtcDisableGeometry(inst.instance);
          inst.enabled = want;
          dynamic_dirty = true;
        }
        any = any || want;
      }
    }
    if (dynamic_dirty) {
      rtcCommitScene(dynamic_scene);
      check("Embree: committing the moving bodies");
      dynamic_dirty = false;
    }
    return any;
  }

  void initContext(ExclusionContext& ctx, const std::vector<char>& slot_excluded, bool coherent) {
    rtcInitIntersectContext(&ctx.context);
    if (coherent) ctx.context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    ctx.slot_excluded = slot_excluded.data();
    ctx.geom_slot = static_geom_slot.data();
    bool static_excluded = false;
    for (const std::uint32_t slot : static_geom_slot) {
      static_excluded = static_excluded || (!slot_excluded.empty() && slot_excluded[slot]);
    }
    if (static_excluded) ctx.context.filter = rejectExcluded;
  }
};

EmbreeScene::EmbreeScene(const TriangleMesh& static_mesh_W, const std::vector<std::uint32_t>& slot_of_triangle,
                         const std::string& device_config)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.device = rtcNewDevice(device_config.c_str());
  if (m.device == nullptr) {
    throw std::runtime_error("Embree: rtcNewDevice(\"" + device_config + "\") failed (error " +
                             std::to_string(static_cast<int>(rtcGetDeviceError(nullptr))) + ")");
  }
  rtcSetDeviceErrorFunction(m.device, recordError, &m.error);

  m.static_scene = rtcNewScene(m.device);
  // Robust: rays through a shared edge or vertex (pixel centres on a regular wall grid) must
  // not slip between the triangles.
  rtcSetSceneFlags(m.static_scene, RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
  rtcSetSceneBuildQuality(m.static_scene, RTC_BUILD_QUALITY_HIGH);
  m.static_geom_slot = attachBySlot(m.device, m.static_scene, static_mesh_W, slot_of_triangle);
  rtcCommitScene(m.static_scene);
  m.check("Embree: building the static scene");

  m.dynamic_scene = rtcNewScene(m.device);
  rtcSetSceneFlags(m.dynamic_scene, RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_DYNAMIC);
  rtcCommitScene(m.dynamic_scene);
  m.check("Embree: creating the moving-body scene");
}

EmbreeScene::~EmbreeScene() {
  Impl& m = *impl_;
  for (Impl::Body& body : m.bodies) {
    for (Impl::Instance& inst : body.instances) {
      rtcReleaseGeometry(inst.instance);
      rtcReleaseScene(inst.part_scene);
    }
  }
  if (m.dynamic_scene) rtcReleaseScene(m.dynamic_scene);
  if (m.static_scene) rtcReleaseScene(m.static_scene);
  if (m.device) rtcReleaseDevice(m.device);
}

std::size_t EmbreeScene::addBody(const TriangleMesh& mesh_B, const std::vector<std::uint32_t>& slot_of_triangle,
                                 const Pose& T_W_B) {
  Impl& m = *impl_;
  Impl::Body body;
  std::vector<std::uint32_t> slots(slot_of_triangle);
  std::sort(slots.begin(), slots.end());
  slots.erase(std::unique(slots.begin(), slots.end()), slots.end());
  for (const std::uint32_t slot : slots) {
    // One scene per part of the body, so a part is switched off by disabling its instance.
    TriangleMesh part;
    part.vertices_m = mesh_B.vertices_m;
    std::vector<std::uint32_t> part_slots;
    for (std::size_t t = 0; t < mesh_B.triangles.size(); ++t) {
      if (slot_of_triangle[t] != slot) continue;
      part.triangles.push_back(mesh_B.triangles[t]);
      part_slots.push_back(slot);
    }
    Impl::Instance inst;
    inst.slot = slot;
    inst.part_scene = rtcNewScene(m.device);
    rtcSetSceneFlags(inst.part_scene, RTC_SCENE_FLAG_ROBUST);
    attachBySlot(m.device, inst.part_scene, part, part_slots);
    rtcCommitScene(inst.part_scene);
    inst.instance = rtcNewGeometry(m.device, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(inst.instance, inst.part_scene);
    rtcSetGeometryTimeStepCount(inst.instance, 1);
    setTransform(inst.instance, T_W_B);
    rtcAttachGeometry(m.dynamic_scene, inst.instance);
    body.instances.push_back(inst);
  }
  m.bodies.push_back(std::move(body));
  m.dynamic_dirty = true;
  m.check("Embree: adding a moving body");
  return m.bodies.size() - 1;
}

void EmbreeScene::setBodyPose(std::size_t body, const Pose& T_W_B) {
  Impl& m = *impl_;
  for (Impl::Instance& inst : m.bodies.at(body).instances) setTransform(inst.instance, T_W_B);
  m.dynamic_dirty = true;
}

void EmbreeScene::renderDepth(const Pose& T_W_C, const DepthCameraParams& camera, const std::vector<char>& slot_excluded,
                              std::vector<float>& z_buffer) {
  Impl& m = *impl_;
  const bool dynamic = m.prepareDynamic(slot_excluded);
  ExclusionContext ctx{};
  m.initContext(ctx, slot_excluded, true);
  RTCIntersectContext plain;
  rtcInitIntersectContext(&plain);
  plain.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;

  const int W = camera.width_px;
  const int H = camera.height_px;
  const Eigen::Matrix3d& R = T_W_C.linear();
  const Eigen::Vector3d dir_W = -R.col(2);
  // Ray origins on the near plane: pixel (r, c) starts at corner_W + c step_x_W + r step_y_W.
  const Eigen::Vector3d corner_W =
      T_W_C * Eigen::Vector3d(camera.pixelCentreX_m(0), camera.pixelCentreY_m(0), camera.near_m);
  const Eigen::Vector3d step_x_W = R.col(0) * camera.pixel_size_m;
  const Eigen::Vector3d step_y_W = -R.col(1) * camera.pixel_size_m;
  // Rays start on the near plane; a hit farther than near - far lies below far (clamped anyway).
  const auto t_max = static_cast<float>(camera.near_m - camera.far_m);
  constexpr float kMinusInf = -std::numeric_limits<float>::infinity();

  alignas(64) RTCRayHit16 packet;
  alignas(64) int valid[kPacket];
  // 4 x 4 pixel tiles: neighbouring rays traverse the same boxes.
  for (int r0 = 0; r0 < H; r0 += 4) {
    for (int c0 = 0; c0 < W; c0 += 4) {
      for (int k = 0; k < kPacket; ++k) {
        const int r = r0 + k / 4;
        const int c = c0 + k % 4;
        valid[k] = (r < H && c < W) ? -1 : 0;
        const Eigen::Vector3d o_W = corner_W + std::min(c, W - 1) * step_x_W + std::min(r, H - 1) * step_y_W;
        setRay(packet, k, o_W.cast<float>(), dir_W.cast<float>(), 0.0f, t_max);
      }
      rtcIntersect16(valid, m.static_scene, &ctx.context, &packet);
      if (dynamic) rtcIntersect16(valid, m.dynamic_scene, &plain, &packet);
      for (int k = 0; k < kPacket; ++k) {
        if (valid[k] == 0) continue;
        const int r = r0 + k / 4;
        const int c = c0 + k % 4;
        z_buffer[static_cast<std::size_t>(r) * W + c] =
            packet.hit.geomID[k] == kInvalid ? kMinusInf
                                             : static_cast<float>(camera.near_m - static_cast<double>(packet.ray.tfar[k]));
      }
    }
  }
  m.check("Embree: rendering a depth image");
}

void EmbreeScene::scan(const Pose& T_W_S, const LaserParams& laser, const std::vector<char>& slot_excluded,
                       std::vector<float>& ranges) {
  Impl& m = *impl_;
  const bool dynamic = m.prepareDynamic(slot_excluded);
  ExclusionContext ctx{};
  m.initContext(ctx, slot_excluded, false);
  RTCIntersectContext plain;
  rtcInitIntersectContext(&plain);

  ranges.assign(laser.beam_count, std::numeric_limits<float>::infinity());
  const Eigen::Vector3f o_W = T_W_S.translation().cast<float>();
  alignas(64) RTCRayHit16 packet;
  alignas(64) int valid[kPacket];
  for (int first = 0; first < laser.beam_count; first += kPacket) {
    for (int k = 0; k < kPacket; ++k) {
      const int i = first + k;
      valid[k] = i < laser.beam_count ? -1 : 0;
      const double angle = laser.beamAngle_rad(std::min(i, laser.beam_count - 1));
      const Eigen::Vector3d d_W = T_W_S.linear() * Eigen::Vector3d(std::cos(angle), std::sin(angle), 0.0);
      setRay(packet, k, o_W, d_W.cast<float>(), static_cast<float>(laser.range_min_m),
             static_cast<float>(laser.range_max_m));
    }
    rtcIntersect16(valid, m.static_scene, &ctx.context, &packet);
    if (dynamic) rtcIntersect16(valid, m.dynamic_scene, &plain, &packet);
    for (int k = 0; k < kPacket && first + k < laser.beam_count; ++k) {
      if (packet.hit.geomID[k] != kInvalid) ranges[first + k] = packet.ray.tfar[k];
    }
  }
  m.check("Embree: casting a laser scan");
}

}  // namespace climbsim::scene
