#include "renderers/tri_aabb/tri_aabb_renderer.h"

#include "renderers/backend_registry.h"

namespace sdfbench {

TriAabbRenderer::TriAabbRenderer(const BackendOptions& options)
    : context_(VulkanContext::Options{options.device, options.validation}),
      runner_(context_, compute_tile_kernels(context_, "tri_aabb.comp"), kTriAabbCounters, options.whitted_passes) {}

void TriAabbRenderer::prepare(const Scene& scene) {
  tables_ = std::make_unique<TriangleBuffers>(context_, scene);
  runner_.set_scene(scene, tables_->bindings());
}

BackendInfo tri_aabb_backend() {
  BackendInfo info;
  info.name = "tri-aabb";
  info.kind = "triangles";
  info.summary = "the thesis' \"traditional\" tracer: a box per instance, every triangle tested (compute kernel)";
  info.counters = true;
  info.create = [](const BackendOptions& options) { return std::make_unique<TriAabbRenderer>(options); };
  return info;
}

}  // namespace sdfbench
