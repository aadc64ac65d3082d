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

// CPU reference: Embree BVH, one scene per mesh plus one instance each, TBB over tiles with
// an explicit thread count; shading is the GLSL program compiled as C++ (cpu_shading.h).
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
  void check_device(const char* what) const;
  void release_scene();

  unsigned threads_;
  RTCDevice device_ = nullptr;
  RTCScene top_ = nullptr;
  std::vector<RTCScene> mesh_scenes_;
  const Scene* scene_ = nullptr;
  std::vector<glm::mat3> normal_to_world_;  // per instance
};

EmbreeRenderer::EmbreeRenderer(const BackendOptions& options) : threads_(cpu_thread_count(options)) {
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

void EmbreeRenderer::prepare(const Scene& scene) {
  release_scene();
  scene_ = &scene;
  for (const Mesh& mesh : scene.meshes) {
    RTCScene mesh_scene = rtcNewScene(device_);
    rtcSetSceneBuildQuality(mesh_scene, RTC_BUILD_QUALITY_HIGH);
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                 3 * sizeof(float), mesh.positions.size()));
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                   3 * sizeof(unsigned), mesh.triangles.size()));
    check_device("allocating mesh buffers");
    for (size_t i = 0; i < mesh.positions.size(); ++i)
      for (int k = 0; k < 3; ++k) vertices[3 * i + k] = mesh.positions[i][k];
    for (size_t i = 0; i < mesh.triangles.size(); ++i)
      for (int k = 0; k < 3; ++k) indices[3 * i + k] = mesh.triangles[i][k];
    rtcCommitGeometry(geometry);
    rtcAttachGeometryByID(mesh_scene, geometry, 0);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(mesh_scene);
    mesh_scenes_.push_back(mesh_scene);
  }
  top_ = rtcNewScene(device_);
  normal_to_world_.clear();
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    const Instance& instance = scene.instances[i];
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(geometry, mesh_scenes_[instance.mesh]);
    const glm::mat4 m = instance.transform.object_to_world();
    rtcSetGeometryTransform(geometry, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &m[0][0]);
    rtcCommitGeometry(geometry);
    rtcAttachGeometryByID(top_, geometry, static_cast<unsigned>(i));  // instID == instance index
    rtcReleaseGeometry(geometry);
    normal_to_world_.push_back(glm::mat3(m));
  }
  rtcCommitScene(top_);
  check_device("building the BVH");
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
  const unsigned index = rh.hit.instID[0];
  const Instance& instance = scene_->instances[index];
  const Mesh& mesh = scene_->meshes[instance.mesh];
  const glm::uvec3 tri = mesh.triangles[rh.hit.primID];
  const glm::vec2 uv(rh.hit.u, rh.hit.v);
  const glm::vec3 n = shading::interpolate_barycentric(mesh.normals[tri.x], mesh.normals[tri.y], mesh.normals[tri.z], uv);
  hit.t = rh.ray.tfar;
  hit.instance = index;
  hit.prim = rh.hit.primID;
  hit.material = instance.material;
  hit.normal = glm::normalize(normal_to_world_[index] * n);
  hit.uv = uv;
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

FrameResult EmbreeRenderer::render(const FrameRequest& request) {
  if (!scene_) throw InternalError("render before prepare");
  return render_cpu_frame(*this, *scene_, make_shading_inputs(*scene_, request), request, threads_, 0u);
}

BackendInfo embree_backend() {
  return {.name = "embree", .kind = BackendKind::CpuBvh,
          .summary = "Embree on the CPU: the reference every image is checked against",
          .vulkan = false, .create = factory<EmbreeRenderer>()};
}

}  // namespace sdfbench
