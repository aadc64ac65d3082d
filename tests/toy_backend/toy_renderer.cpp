#include "tests/toy_backend/toy_renderer.h"

#include "renderers/cpu_frame.h"
#include "renderers/frame_params.h"
#include "util/cpu_info.h"
#include "util/error.h"

namespace sdfbench::toy {
namespace {

class ToyRenderer : public Renderer {
 public:
  explicit ToyRenderer(const BackendOptions& options)
      : reverse_(options.params.text("toy_order") == "reverse"), threads_(cpu_thread_count(options)) {}
  std::string name() const override { return "toy"; }
  std::string device_name() const override { return cpu_model(); }
  std::string driver_name() const override { return "toy brute-force tracer"; }
  void prepare(const Scene& scene) override { scene_ = &scene; }
  FrameResult render(const FrameRequest& request) override {
    if (!scene_) throw InternalError("render before prepare");
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
        float t = 0;  // in the ray's own units: the object-space ray keeps the world's t (a similarity)
        glm::vec2 uv;
        if (!shading::ray_triangle(o, d, mesh.positions[tri.x], mesh.positions[tri.y], mesh.positions[tri.z], t, uv) ||
            !(t > 0.0f && t < tmax))
          continue;
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
  info.kind = BackendKind::Triangles;
  info.summary = "a test's toy: every triangle of every instance for every ray, on the CPU";
  info.vulkan = false;
  info.params = {{"toy_order", ParamKind::Choice, "forward",
                  "the order the toy tests instances in (the image is the same either way)", "toy", {"forward", "reverse"}}};
  info.in_table = false;
  info.create = factory<ToyRenderer>();
  return info;
}

}  // namespace sdfbench::toy
