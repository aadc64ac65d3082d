#pragma once
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "renderers/embree/embree_api.h"
#include "renderers/renderer.h"
#include "renderers/shading/gpu_types.h"

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

// Its entry in the backend registry (renderers/backend_registry.h).
struct BackendInfo;
BackendInfo embree_backend();

}  // namespace sdfbench
