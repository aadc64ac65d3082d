#include <algorithm>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "renderers/backend.h"
#include "renderers/cpu_frame.h"
#include "renderers/embree/embree_api.h"
#include "renderers/renderer.h"
#include "renderers/shading/gpu_types.h"
#include "util/cpu_info.h"
#include "util/error.h"

namespace sdfbench {

// CPU reference: Embree BVH, one scene per mesh plus one instance each (--embree-scene
// instanced, the reference) or one scene of every instance's triangles in world space (flat),
// TBB over tiles with an explicit thread count; shading is the GLSL program compiled as C++
// (cpu_shading.h). --embree-rays packets traces the primary rays of 8 pixels of a row as one
// packet (rtcIntersect8) and, in shadow mode, their shadow rays too (rtcOccluded8: a first
// shading pass records each pixel's shadow rays, the second shades with their answers), as
// Embree's tutorials trace coherent rays; single (the reference) traces every ray alone.
class EmbreeRenderer : public Renderer {
 public:
  explicit EmbreeRenderer(const BackendOptions& options);
  ~EmbreeRenderer() override;
  std::string name() const override { return "embree"; }
  std::string device_name() const override;
  std::string driver_name() const override;
  void prepare(const Scene& scene) override;
  FrameResult render(const FrameRequest& request) override;

  // The backend's two queries, as the shading program calls them. Embree exposes no traversal
  // counts: instrumented frames leave `counts` alone and report no counters.
  bool closest_hit(shading::Ray ray, float tmax, shading::Hit& hit, shading::PixelCounts* counts) const;
  bool any_hit(shading::Ray ray, float tmax, shading::PixelCounts* counts) const;
  float mesh_hit_tolerance() const { return 0.0f; }  // ray-triangle hits lie on the triangle

 private:
  // The hit of a query's result (ray and hit as Embree filled them).
  void fill_hit(unsigned geom, unsigned inst, unsigned prim, float u, float v, float t, shading::Hit& hit) const;
  void check_device(const char* what) const;
  void release_scene();
  RTCGeometry triangle_geometry(const Mesh& mesh, const glm::mat4& to_world);
  FrameResult render_packets(const FrameRequest& request) const;

  bool packets_ = false, flat_ = false;
  unsigned threads_;
  RTCDevice device_ = nullptr;
  RTCScene top_ = nullptr;
  std::vector<RTCScene> mesh_scenes_;
  const Scene* scene_ = nullptr;
  std::vector<glm::mat3> normal_to_world_;  // per instance
};

EmbreeRenderer::EmbreeRenderer(const BackendOptions& options)
    : packets_(options.params.text("embree_rays") == "packets"),
      flat_(options.params.text("embree_scene") == "flat"),
      threads_(cpu_thread_count(options)) {
  const std::string config = "threads=" + std::to_string(threads_);
  device_ = rtcNewDevice(config.c_str());
  if (!device_) throw Error("Embree: rtcNewDevice failed (error " + std::to_string(rtcGetDeviceError(nullptr)) + ")");
}

EmbreeRenderer::~EmbreeRenderer() {
  release_scene();
  rtcReleaseDevice(device_);
}

std::string EmbreeRenderer::device_name() const { return cpu_model() + " (" + std::to_string(threads_) + " threads)"; }

std::string EmbreeRenderer::driver_name() const {
  return "Embree " + embree::version();
}

void EmbreeRenderer::check_device(const char* what) const {
  const RTCError error = rtcGetDeviceError(device_);
  if (error != RTC_ERROR_NONE) throw Error(std::string("Embree: ") + what + " failed (error " + std::to_string(error) + ")");
}

void EmbreeRenderer::release_scene() {
  if (top_) rtcReleaseScene(top_);
  for (RTCScene s : mesh_scenes_) rtcReleaseScene(s);
  top_ = nullptr;
  mesh_scenes_.clear();
}

RTCGeometry EmbreeRenderer::triangle_geometry(const Mesh& mesh, const glm::mat4& to_world) {
  RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                               3 * sizeof(float), mesh.positions.size()));
  auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                 3 * sizeof(unsigned), mesh.triangles.size()));
  check_device("allocating mesh buffers");
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::vec3 p = glm::vec3(to_world * glm::vec4(mesh.positions[i], 1.0f));
    for (int k = 0; k < 3; ++k) vertices[3 * i + k] = p[k];
  }
  for (size_t i = 0; i < mesh.triangles.size(); ++i)
    for (int k = 0; k < 3; ++k) indices[3 * i + k] = mesh.triangles[i][k];
  rtcCommitGeometry(geometry);
  return geometry;
}

void EmbreeRenderer::prepare(const Scene& scene) {
  release_scene();
  scene_ = &scene;
  top_ = rtcNewScene(device_);
  normal_to_world_.clear();
  for (const Instance& instance : scene.instances) normal_to_world_.push_back(glm::mat3(instance.transform.object_to_world()));
  if (flat_) {  // one geometry per instance, its triangles in world space: geomID == instance index
    rtcSetSceneBuildQuality(top_, RTC_BUILD_QUALITY_HIGH);
    for (size_t i = 0; i < scene.instances.size(); ++i) {
      const Instance& instance = scene.instances[i];
      RTCGeometry geometry = triangle_geometry(scene.meshes[instance.mesh], instance.transform.object_to_world());
      rtcAttachGeometryByID(top_, geometry, static_cast<unsigned>(i));
      rtcReleaseGeometry(geometry);
    }
    rtcCommitScene(top_);
    check_device("building the BVH");
    return;
  }
  for (const Mesh& mesh : scene.meshes) {
    RTCScene mesh_scene = rtcNewScene(device_);
    rtcSetSceneBuildQuality(mesh_scene, RTC_BUILD_QUALITY_HIGH);
    RTCGeometry geometry = triangle_geometry(mesh, glm::mat4(1.0f));
    rtcAttachGeometryByID(mesh_scene, geometry, 0);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(mesh_scene);
    mesh_scenes_.push_back(mesh_scene);
  }
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    const Instance& instance = scene.instances[i];
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(geometry, mesh_scenes_[instance.mesh]);
    const glm::mat4 m = instance.transform.object_to_world();
    rtcSetGeometryTransform(geometry, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &m[0][0]);
    rtcCommitGeometry(geometry);
    rtcAttachGeometryByID(top_, geometry, static_cast<unsigned>(i));  // instID == instance index
    rtcReleaseGeometry(geometry);
  }
  rtcCommitScene(top_);
  check_device("building the BVH");
}

void EmbreeRenderer::fill_hit(unsigned geom, unsigned inst, unsigned prim, float u, float v, float t, shading::Hit& hit) const {
  const unsigned index = flat_ ? geom : inst;
  const Instance& instance = scene_->instances[index];
  const Mesh& mesh = scene_->meshes[instance.mesh];
  const glm::uvec3 tri = mesh.triangles[prim];
  const glm::vec2 uv(u, v);
  const glm::vec3 n = shading::interpolate_barycentric(mesh.normals[tri.x], mesh.normals[tri.y], mesh.normals[tri.z], uv);
  hit.t = t;
  hit.instance = index;
  hit.prim = prim;
  hit.material = instance.material;
  hit.normal = glm::normalize(normal_to_world_[index] * n);
  hit.uv = uv;
}

bool EmbreeRenderer::closest_hit(shading::Ray ray, float tmax, shading::Hit& hit, shading::PixelCounts*) const {
  RTCRayHit rh{};
  rh.ray.org_x = ray.origin.x, rh.ray.org_y = ray.origin.y, rh.ray.org_z = ray.origin.z;
  rh.ray.dir_x = ray.dir.x, rh.ray.dir_y = ray.dir.y, rh.ray.dir_z = ray.dir.z;
  rh.ray.tnear = 0.0f;
  rh.ray.tfar = tmax;
  rh.ray.mask = 0xffffffffu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  embree::intersect1(top_, rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  fill_hit(rh.hit.geomID, rh.hit.instID[0], rh.hit.primID, rh.hit.u, rh.hit.v, rh.ray.tfar, hit);
  return true;
}

bool EmbreeRenderer::any_hit(shading::Ray ray, float tmax, shading::PixelCounts*) const {
  RTCRay r{};
  r.org_x = ray.origin.x, r.org_y = ray.origin.y, r.org_z = ray.origin.z;
  r.dir_x = ray.dir.x, r.dir_y = ray.dir.y, r.dir_z = ray.dir.z;
  r.tnear = 0.0f;
  r.tfar = tmax;
  r.mask = 0xffffffffu;
  embree::occluded1(top_, r);
  return r.tfar < 0.0f;  // Embree sets tfar to -inf on occlusion
}

namespace {

constexpr uint32_t kPacket = 8;

// The tracer of one pixel of a packet: its primary hit was traced with the packet; in shadow
// mode, a recording pass collects its shadow rays (answered "unoccluded") and the shading pass
// replays their packet answers. The sequence of shadow rays does not depend on their answers
// (occlusion only dims a light), so both passes ask the same rays; any other query is traced
// alone. Per tile, so its state needs no lock.
class PacketTracer {
 public:
  struct Primary {
    shading::Ray ray;
    bool found = false;
    shading::Hit hit;
  };
  struct Shadow {
    shading::Ray ray;
    float tmax;
    bool occluded = false;
  };

  PacketTracer(const EmbreeRenderer& embree, float primary_tmax) : embree_(embree), primary_tmax_(primary_tmax) {}

  bool closest_hit(shading::Ray ray, float tmax, shading::Hit& hit, shading::PixelCounts* counts) const {
    const Primary& p = primaries[pixel];
    if (first_ && tmax == primary_tmax_ && ray.origin == p.ray.origin && ray.dir == p.ray.dir) {
      first_ = false;
      if (p.found) hit = p.hit;
      return p.found;
    }
    first_ = false;
    return embree_.closest_hit(ray, tmax, hit, counts);
  }
  bool any_hit(shading::Ray ray, float tmax, shading::PixelCounts* counts) const {
    std::vector<Shadow>& rays = shadows[pixel];
    if (recording) {
      rays.push_back({ray, tmax});
      return false;
    }
    if (next_ < rays.size() && rays[next_].ray.origin == ray.origin && rays[next_].ray.dir == ray.dir && rays[next_].tmax == tmax)
      return rays[next_++].occluded;
    return embree_.any_hit(ray, tmax, counts);
  }
  float mesh_hit_tolerance() const { return 0.0f; }

  void begin_pixel(uint32_t i) const {
    pixel = i;
    first_ = true;
    next_ = 0;
  }

  mutable Primary primaries[kPacket];
  mutable std::vector<Shadow> shadows[kPacket];
  mutable uint32_t pixel = 0;
  mutable bool recording = false;

 private:
  const EmbreeRenderer& embree_;
  const float primary_tmax_;
  mutable bool first_ = true;
  mutable size_t next_ = 0;
};

void set_lane(RTCRay8& r, uint32_t i, const shading::Ray& ray, float tmax) {
  r.org_x[i] = ray.origin.x, r.org_y[i] = ray.origin.y, r.org_z[i] = ray.origin.z;
  r.dir_x[i] = ray.dir.x, r.dir_y[i] = ray.dir.y, r.dir_z[i] = ray.dir.z;
  r.tnear[i] = 0.0f;
  r.tfar[i] = tmax;
  r.mask[i] = 0xffffffffu;
  r.time[i] = 0.0f;
  r.flags[i] = 0;
  r.id[i] = i;
}

}  // namespace

FrameResult EmbreeRenderer::render_packets(const FrameRequest& request) const {
  const ShadingInputs inputs = make_shading_inputs(*scene_, request);
  const float primary_tmax = inputs.frame.tracing.z;
  const bool shadows = request.mode == RenderMode::Shadow;
  return render_cpu_frame_tiles(request, threads_, 0u, [&](const auto& rows, const auto& cols, CpuFrameTarget& target) {
    PacketTracer tracer(*this, primary_tmax);
    shading::CpuShading<PacketTracer> program = cpu_program(tracer, *scene_, inputs);
    for (uint32_t y = rows.begin(); y < rows.end(); ++y)
      for (uint32_t x0 = cols.begin(); x0 < cols.end(); x0 += kPacket) {
        const uint32_t n = std::min(kPacket, cols.end() - x0);
        alignas(32) int valid[kPacket];
        alignas(32) RTCRayHit8 rh{};
        for (uint32_t i = 0; i < kPacket; ++i) {
          valid[i] = i < n ? -1 : 0;
          if (i >= n) continue;
          const shading::PathEntry e = program.primary_ray(glm::uvec2(x0 + i, y));
          tracer.primaries[i].ray = shading::Ray{glm::vec3(e.origin), glm::vec3(e.dir)};
          set_lane(rh.ray, i, tracer.primaries[i].ray, primary_tmax);
          rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
          rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
        }
        embree::intersect8(valid, top_, rh);
        for (uint32_t i = 0; i < n; ++i) {
          PacketTracer::Primary& p = tracer.primaries[i];
          p.found = rh.hit.geomID[i] != RTC_INVALID_GEOMETRY_ID;
          if (p.found) fill_hit(rh.hit.geomID[i], rh.hit.instID[0][i], rh.hit.primID[i], rh.hit.u[i], rh.hit.v[i], rh.ray.tfar[i], p.hit);
          tracer.shadows[i].clear();
        }
        if (shadows) {  // record each pixel's shadow rays, then trace the k-th of every pixel as one packet
          tracer.recording = true;
          size_t most = 0;
          for (uint32_t i = 0; i < n; ++i) {
            shading::PixelAov aov;
            tracer.begin_pixel(i);
            program.shade_pixel(glm::uvec2(x0 + i, y), aov, nullptr);
            most = std::max(most, tracer.shadows[i].size());
          }
          tracer.recording = false;
          for (size_t k = 0; k < most; ++k) {
            alignas(32) RTCRay8 r{};
            for (uint32_t i = 0; i < kPacket; ++i) {
              valid[i] = i < n && k < tracer.shadows[i].size() ? -1 : 0;
              if (valid[i]) set_lane(r, i, tracer.shadows[i][k].ray, tracer.shadows[i][k].tmax);
            }
            embree::occluded8(valid, top_, r);
            for (uint32_t i = 0; i < n; ++i)
              if (valid[i]) tracer.shadows[i][k].occluded = r.tfar[i] < 0.0f;  // -inf on occlusion
          }
        }
        for (uint32_t i = 0; i < n; ++i) {
          shading::PixelAov aov;
          shading::PixelCounts work{};
          tracer.begin_pixel(i);
          const glm::vec4 color = program.shade_pixel(glm::uvec2(x0 + i, y), aov, request.counters ? &work : nullptr);
          target.store(static_cast<size_t>(y) * request.width + x0 + i, color, aov, work);
        }
      }
  });
}

FrameResult EmbreeRenderer::render(const FrameRequest& request) {
  if (!scene_) throw InternalError("render before prepare");
  if (packets_) return render_packets(request);
  return render_cpu_frame(*this, *scene_, make_shading_inputs(*scene_, request), request, threads_, 0u);
}

BackendInfo embree_backend() {
  BackendInfo info;
  info.name = "embree";
  info.kind = BackendKind::CpuBvh;
  info.summary = "Embree on the CPU: the reference every image is checked against (single rays over instances)";
  const std::string group = "Embree (embree)";
  info.params.push_back({"embree_rays", ParamKind::Choice, "single",
                         "single: every ray alone (rtcIntersect1, the reference); packets: the primary rays of 8 pixels, "
                         "and in shadow mode their shadow rays, as one packet (rtcIntersect8/rtcOccluded8)",
                         group, {"single", "packets"}});
  info.params.push_back({"embree_scene", ParamKind::Choice, "instanced",
                         "instanced: one scene per mesh and an instance each (the reference); flat: one scene of every "
                         "instance's triangles in world space",
                         group, {"instanced", "flat"}});
  info.vulkan = false;
  info.create = factory<EmbreeRenderer>();
  return info;
}

}  // namespace sdfbench
