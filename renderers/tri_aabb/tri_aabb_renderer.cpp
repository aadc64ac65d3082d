#include "renderers/tri_aabb/tri_aabb_renderer.h"

#include "renderers/backend_registry.h"

namespace sdfbench {

TriAabbRenderer::TriAabbRenderer(const BackendOptions& options)
    : VulkanRenderer(options),
      runner_(context_, compute_tile_kernels(context_, "tri_aabb.comp"), kTriAabbCounters, options.whitted_passes) {}

void TriAabbRenderer::prepare(const Scene& scene) {
  tables_ = std::make_unique<TriangleBuffers>(context_, scene);
  runner_.set_scene(scene, tables_->bindings());
}

BackendInfo tri_aabb_backend() {
  return {.name = "tri-aabb", .kind = "triangles",
          .summary = "the thesis' \"traditional\" tracer: a box per instance, every triangle tested (compute kernel)",
          .counters = true, .create = factory<TriAabbRenderer>()};
}

}  // namespace sdfbench
