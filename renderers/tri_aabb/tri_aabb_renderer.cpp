#include <memory>

#include "renderers/backend.h"
#include "renderers/renderer.h"
#include "renderers/vulkan/triangle_buffers.h"
#include "renderers/vulkan/vulkan_frame_runner.h"
#include "renderers/vulkan/vulkan_renderer.h"

namespace sdfbench {

// Vulkan compute, per-instance AABB then every triangle (thesis table 6.3).
class TriAabbRenderer : public VulkanRenderer {
 public:
  explicit TriAabbRenderer(const BackendOptions& options);
  std::string name() const override { return "tri-aabb"; }
  void prepare(const Scene& scene) override;
  FrameResult render(const FrameRequest& request) override { return runner_.run(request); }

 private:
  std::unique_ptr<TriangleBuffers> tables_;
  VulkanFrameRunner runner_;  // declared last: destroyed first, before the buffers it binds
};

TriAabbRenderer::TriAabbRenderer(const BackendOptions& options)
    : VulkanRenderer(options),
      runner_(context_, compute_tile_kernels(context_, "tri_aabb.comp"), kTriAabbCounters, options.whitted_passes) {}

void TriAabbRenderer::prepare(const Scene& scene) {
  tables_ = std::make_unique<TriangleBuffers>(context_, scene);
  runner_.set_scene(scene, tables_->bindings());
}

BackendInfo tri_aabb_backend() {
  return {.name = "tri-aabb", .kind = BackendKind::Triangles,
          .summary = "the thesis' \"traditional\" tracer: a box per instance, every triangle tested (compute kernel)",
          .counters = true, .create = factory<TriAabbRenderer>()};
}

}  // namespace sdfbench
