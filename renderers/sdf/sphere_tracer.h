#pragma once
// CPU reference sphere tracer (Hart 1996) over the scene SDF, with the parameters the GPU
// backends use; its closest_hit/any_hit plug into the shared shading program.
#include <cstdint>
#include <string>

#include "renderers/sdf/exact_hit.h"
#include "renderers/sdf/scene_hash.h"
#include "renderers/sdf/traced_distance.h"
#include "renderers/shading/gpu_types.h"
#include "scenes/scene.h"

namespace sdfbench::sdf {

// Where a converged ray hits: `exact` intersects it with the triangles listed there (exact_hit.h;
// the default: t, normal and uv where the ray meets the surface, as in Embree); `thesis` takes the
// converged point and the closest point on the nearest triangle (thesis 5.2); `field` (sdf-bricks,
// sdf-global) the sampled field's own zero crossing and gradient normal (brick_trace.glsl).
enum class HitMode { exact, thesis, field };
std::string to_string(HitMode hit);

struct SphereTraceParams {
  uint32_t max_steps = 512;
  HitMode hit = HitMode::exact;
  // --hit exact: hit when the distance drops below this fraction of the pixel's footprint at t
  // (never below float precision at the point); --hit thesis uses hit_epsilon instead.
  float footprint = 0.25f;
  float hit_epsilon = 5e-6f;  // --hit thesis: hit when the distance drops below this x the scene scale (2e-5 left ~1 % silhouette false hits)
  // --over-relax: over-relaxed sphere tracing (Keinert et al. 2014), steps of this x the distance
  // while consecutive unbounding spheres overlap; 1 (the thesis' plain sphere tracing) is off.
  float over_relax = 1.0f;
  // --cell-bound (Vulkan SDF kernels): each octree leaf (or hash cell) keeps a lower bound on the
  // distance from it to any listed surface, and a step from a leaf whose bound is above 0 crosses
  // the leaf and goes the bound beyond, evaluating no instance. Off: the thesis' step everywhere.
  bool cell_bound = false;
  // --storage-tables (Vulkan SDF kernels): the structure's tables in storage buffers instead of
  // texel buffers (sdf_scene_distance.glsl); the same data and results, another memory path.
  bool storage_tables = false;
};

// `counts` (nullable): adds the steps, instance and triangle evaluations and box tests, counted
// as the Vulkan kernels count them.
class SphereTracer {
 public:
  SphereTracer(const Scene& scene, const SceneSdf& sdf, const SphereTraceParams& params);
  bool closest_hit(shading::Ray ray, float tmax, shading::Hit& hit, shading::PixelCounts* counts) const;
  bool any_hit(shading::Ray ray, float tmax, shading::PixelCounts* counts) const;
  // How far off the surface a hit can lie: 0 for --hit exact; --hit thesis's point lies within
  // epsilon, and a ray leaving it starts kThesisOffsetEpsilons epsilons off (well outside).
  float mesh_hit_tolerance() const { return params_.hit == HitMode::exact ? 0.0f : kThesisOffsetEpsilons * epsilon_; }
  // The frame's camera: --hit exact's footprint follows its pixel angle (before rendering it).
  void set_frame(const shading::FrameParams& frame);

 private:
  static constexpr float kThesisOffsetEpsilons = 20.0f;  // SDF_THESIS_OFFSET_EPSILONS
  enum class MarchEnd { converged, left, out_of_steps };
  struct SurfaceHit {
    float t;
    uint32_t instance, triangle;
    glm::vec2 uv;
  };
  // The hit threshold at t (sdf_trace.comp's hit_epsilon).
  float epsilon_at(const shading::Ray& ray, float t) const;
  // Sphere tracing from t towards t1 with `steps` of the budget spent; `last`: the distance at
  // t_last, the last point queried (sdf_trace.comp's march).
  MarchEnd march(const shading::Ray& ray, float t1, float& t, uint32_t& steps, SceneDistance& last, float& t_last,
                 shading::PixelCounts* counts) const;
  // exact_crossing() of the ray with an instance's mesh over [t_lo, t_hi], its tests counted.
  bool instance_crossing(const shading::Ray& ray, uint32_t instance_id, float t_lo, float t_hi, Crossing& crossing,
                         shading::PixelCounts* counts) const;
  // The earliest exact crossing in [t - epsilon, t + epsilon] around a converged point: of the
  // instance nearest to it, and of every other instance its leaf lists whose box meets that window.
  // Where instances overlap, another one's surface can cross the window before the nearest one's
  // (sdf_trace.comp's window_crossing).
  bool window_crossing(const shading::Ray& ray, float t, float epsilon, uint32_t nearest, SurfaceHit& hit,
                       shading::PixelCounts* counts) const;
  // The first surface before tmax (sdf_trace.comp's trace_sdf).
  bool trace(const shading::Ray& ray, float tmax, SurfaceHit& hit, shading::PixelCounts* counts) const;

  const Scene& scene_;
  const SceneSdf& sdf_;
  TraceCulling culling_;
  SphereTraceParams params_;
  float epsilon_;     // --hit thesis: hit_epsilon x the scene scale
  float cone_ = 0.0f;  // --hit exact: footprint x the angle of one pixel (set_frame)
};

}  // namespace sdfbench::sdf
