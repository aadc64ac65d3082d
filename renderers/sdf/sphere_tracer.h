#pragma once
// CPU reference sphere tracer (Hart 1996) over the scene SDF, with the parameters the GPU
// backends use; its closest_hit/any_hit plug into the shared shading program.
#include <cstdint>

#include "renderers/sdf/scene_hash.h"
#include "renderers/sdf/traced_distance.h"
#include "renderers/shading/gpu_types.h"
#include "scenes/scene.h"

namespace sdfbench::sdf {

struct SphereTraceParams {
  uint32_t max_steps = 512;
  float hit_epsilon = 5e-6f;  // hit when the distance drops below this x the scene scale (2e-5 left ~1 % silhouette false hits)
};

// `counts` (nullable): adds the steps, instance and triangle evaluations and box tests, counted
// as the Vulkan kernels count them.
class SphereTracer {
 public:
  SphereTracer(const Scene& scene, const SceneSdf& sdf, const SphereTraceParams& params);
  bool closest_hit(shading::Ray ray, float tmax, shading::Hit& hit, shading::PixelCounts* counts) const;
  bool any_hit(shading::Ray ray, float tmax, shading::PixelCounts* counts) const;
  float epsilon() const { return epsilon_; }

 private:
  // March along the ray inside the hash box; returns the hit's t or a negative value.
  float march(const shading::Ray& ray, float tmax, SceneDistance& at_hit, shading::PixelCounts* counts) const;

  const Scene& scene_;
  const SceneSdf& sdf_;
  TraceCulling culling_;
  SphereTraceParams params_;
  float epsilon_;
};

}  // namespace sdfbench::sdf
