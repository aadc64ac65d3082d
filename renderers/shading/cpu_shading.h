#pragma once
// The GLSL shading program compiled as C++ with GLM: CPU backends render with the very same
// source as the Vulkan kernels (shading.glsl), not a rewrite.
#include "renderers/shading/gpu_types.h"

namespace sdfbench::shading {

// Tracer must provide closest_hit(Ray, float, Hit&, PixelCounts*), any_hit(Ray, float,
// PixelCounts*) and mesh_hit_tolerance(), const; they add their work to the counts when given some (instrumented frames).
template <class Tracer>
class CpuShading {
 public:
  CpuShading(const Tracer& tracer, const FrameParams& frame_params, const GpuMaterial* material_table,
             const GpuLight* light_table, const vec4* texel_table /* nullptr: no textures */,
             const GpuImplicitObject* implicit_object_table, const GpuImplicitNode* implicit_node_table)
      : tracer_(tracer),
        frame(frame_params),
        materials(material_table),
        lights(light_table),
        texels(texel_table),
        implicit_objects(implicit_object_table),
        implicit_nodes(implicit_node_table) {}

 private:
  const Tracer& tracer_;
  const FrameParams frame;
  const GpuMaterial* const materials;
  const GpuLight* const lights;
  const vec4* const texels;
  const GpuImplicitObject* const implicit_objects;  // frame.limits.y of them
  const GpuImplicitNode* const implicit_nodes;
  PathEntry stack[STACK_SIZE];  // the ray stack of the pixel being shaded
  PixelCounts* counts_ = nullptr;  // the pixel's work counts, in instrumented frames

  bool closest_hit(Ray ray, float tmax, Hit& hit) { return tracer_.closest_hit(ray, tmax, hit, counts_); }
  bool any_hit(Ray ray, float tmax) { return tracer_.any_hit(ray, tmax, counts_); }
  float mesh_hit_tolerance() const { return tracer_.mesh_hit_tolerance(); }
  vec4 texel_at(uint index) const { return texels[index]; }
  bool has_textures() const { return texels != nullptr; }
  bool has_implicits() const { return frame.limits.y > 0u; }
  uint shading_mode() const { return frame.image.z; }
  PathEntry stack_load(uint i) const { return stack[i]; }
  void stack_store(uint i, const PathEntry& e) { stack[i] = e; }

 public:
#include "shading.glsl"

  // All of a pixel's rays at once (as the Vulkan kernel, but on a driver with a loop cap); their
  // work is added to `counts` unless it is null.
  vec4 shade_pixel(uvec2 pixel, PixelAov& aov, PixelCounts* counts) {
    counts_ = counts;
    PixelState s;
    begin_pixel(s, aov);
    trace_ray(primary_ray(pixel), s, aov);
    while (s.counters.x > 0u) trace_ray(pop_ray(s), s, aov);
    aov.rays = s.counters.y;
    return pixel_color(s);
  }
};

}  // namespace sdfbench::shading
