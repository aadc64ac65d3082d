#include "tests/toy_backend/toy_renderer.h"

#include <limits>

#include "renderers/cpu_frame.h"
#include "renderers/frame_params.h"
#include "util/cpu_info.h"
#include "util/error.h"

namespace sdfbench::toy {
namespace {

// Möller-Trumbore; t in the ray's own units (the object-space ray keeps the world's t under a
// similarity transform).
bool intersect(const glm::vec3& o, const glm::vec3& d, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, float tmax,
               float& t, glm::vec2& uv) {
  const glm::vec3 e1 = b - a, e2 = c - a, p = glm::cross(d, e2);
  const float det = glm::dot(e1, p);
  if (det == 0.0f) return false;
  const float inv = 1.0f / det;
  const glm::vec3 s = o - a;
  const float u = glm::dot(s, p) * inv;
  if (u < 0.0f || u > 1.0f) return false;
  const glm::vec3 q = glm::cross(s, e1);
  const float v = glm::dot(d, q) * inv;
  if (v < 0.0f || u + v > 1.0f) return false;
  t = glm::dot(e2, q) * inv;
  uv = {u, v};
  return t > 0.0f && t < tmax;
}

class ToyRenderer : public Renderer {
 public:
  explicit ToyRenderer(const BackendOptions& options)
      : reverse_(options.params.text("toy_order") == "reverse"), threads_(cpu_thread_count(options)) {}
  std::string name() const override { return "toy"; }
  std::string device_name() const override { return cpu_model(); }
  std::string driver_name() const override { return "toy brute-force tracer"; }
  void prepare(const Scene& scene) override { scene_ = &scene; }
  FrameResult render(const FrameRequest& request) override {
    if (!scene_) throw Error("internal: render before prepare");
    return render_cpu_frame(*this, *scene_, make_shading_inputs(*scene_, request), request, threads_, 0u);
  }

  bool closest_hit(shading::Ray ray, float tmax, shading::Hit& hit, shading::PixelCounts*) const {
    bool found = false;
    const size_t n = scene_->instances.size();
    for (size_t k = 0; k < n; ++k) {
      const size_t index = reverse_ ? n - 1 - k : k;  // --toy-order: the same image either way
      const Instance& instance = scene_->instances[index];
      const Mesh& mesh = scene_->meshes[instance.mesh];
      const glm::mat4 to_object = instance.transform.world_to_object();
      const glm::vec3 o = glm::vec3(to_object * glm::vec4(ray.origin, 1.0f)), d = glm::vec3(to_object * glm::vec4(ray.dir, 0.0f));
      for (size_t f = 0; f < mesh.triangles.size(); ++f) {
        const glm::uvec3 tri = mesh.triangles[f];
        float t = 0;
        glm::vec2 uv;
        if (!intersect(o, d, mesh.positions[tri.x], mesh.positions[tri.y], mesh.positions[tri.z], tmax, t, uv)) continue;
        tmax = t;
        found = true;
        const glm::vec3 normal =
            shading::interpolate_barycentric(mesh.normals[tri.x], mesh.normals[tri.y], mesh.normals[tri.z], uv);
        hit = {t, static_cast<uint32_t>(index), static_cast<uint32_t>(f), instance.material,
               glm::normalize(instance.transform.rotation * normal), uv};
      }
    }
    return found;
  }
  float mesh_hit_tolerance() const { return 0.0f; }  // ray-triangle hits lie on the triangle
  bool any_hit(shading::Ray ray, float tmax, shading::PixelCounts* counts) const {
    shading::Hit hit;
    return closest_hit(ray, tmax, hit, counts);
  }

 private:
  bool reverse_;
  unsigned threads_;
  const Scene* scene_ = nullptr;
};

}  // namespace

BackendInfo toy_backend() {
  BackendInfo info;
  info.name = "toy";
  info.kind = "triangles";
  info.summary = "a test's toy: every triangle of every instance for every ray, on the CPU";
  info.vulkan = false;
  info.params = {{"toy_order", ParamKind::Choice, "forward",
                  "the order the toy tests instances in (the image is the same either way)", "toy", {"forward", "reverse"}}};
  info.in_table = false;
  info.create = factory<ToyRenderer>();
  return info;
}

}  // namespace sdfbench::toy
