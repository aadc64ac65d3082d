#pragma once
// The GLSL shading program compiled as C++ with GLM: CPU backends render with the very same
// source as the Vulkan kernels (shading.glsl), not a rewrite.
#include "renderers/shading/gpu_types.h"

namespace sdfbench::shading {

// Tracer must provide closest_hit(Ray, float, Hit&) and any_hit(Ray, float), const.
template <class Tracer>
class CpuShading {
 public:
  CpuShading(const Tracer& tracer, const FrameParams& frame_params, const GpuMaterial* material_table,
             const GpuLight* light_table)
      : tracer_(tracer), frame(frame_params), materials(material_table), lights(light_table) {}

 private:
  const Tracer& tracer_;
  const FrameParams frame;
  const GpuMaterial* const materials;
  const GpuLight* const lights;

  bool closest_hit(Ray ray, float tmax, Hit& hit) { return tracer_.closest_hit(ray, tmax, hit); }
  bool any_hit(Ray ray, float tmax) { return tracer_.any_hit(ray, tmax); }

 public:
#include "shading.glsl"
};

}  // namespace sdfbench::shading
