#include <chrono>
#include <memory>

#include "renderers/backend.h"
#include "renderers/renderer.h"
#include "renderers/vk_rt/acceleration_structures.h"
#include "renderers/vk_rt/rt_functions.h"
#include "renderers/vk_rt/rt_pipeline.h"
#include "renderers/vulkan/triangle_buffers.h"
#include "renderers/vulkan/vulkan_context.h"
#include "renderers/vulkan/vulkan_frame_runner.h"
#include "util/error.h"

namespace sdfbench {

// The driver's ray tracing (VK_KHR_ray_tracing_pipeline): its acceleration structures, traversed
// by hardware or by the driver's software path, shaded like every other backend. The work counters
// are n/a: the traversal is the driver's.
class VkRtRenderer : public Renderer {
 public:
  // Throws Error "vk-rt: device 'X' lacks ..." on a device without ray-tracing pipelines.
  explicit VkRtRenderer(const BackendOptions& options);
  std::string name() const override { return "vk-rt"; }
  std::string device_name() const override { return context_->info().name; }
  std::string driver_name() const override { return context_->info().driver + " " + context_->info().driver_info; }
  void prepare(const Scene& scene) override;
  FrameResult render(const FrameRequest& request) override { return runner_->run(request); }
  uint32_t validation_messages() const override { return context_->validation_messages(); }
  std::optional<StructureStats> structure_stats() const override { return stats_; }

 private:
  // Destroyed in reverse: the runner (and its pipelines) before the structures and tables it binds.
  std::unique_ptr<VulkanContext> context_;
  std::unique_ptr<RayTracingFunctions> functions_;
  std::unique_ptr<TriangleBuffers> tables_;
  std::unique_ptr<AccelerationStructures> structures_;
  std::unique_ptr<VulkanFrameRunner> runner_;
  std::optional<StructureStats> stats_;
};

VkRtRenderer::VkRtRenderer(const BackendOptions& options) {
  VulkanContext::Options context_options{options.device, options.validation};
  context_options.ray_tracing = true;
  try {
    context_ = std::make_unique<VulkanContext>(context_options);
  } catch (const Error& e) {
    throw Error(std::string("vk-rt: ") + e.what());
  }
  functions_ = std::make_unique<RayTracingFunctions>(*context_);
  // No counters (the traversal is the driver's); whitted in passes only where a loop cap needs it.
  runner_ = std::make_unique<VulkanFrameRunner>(*context_, ray_tracing_tile_kernels(*context_, *functions_), 0u,
                                                options.whitted_passes);
}

void VkRtRenderer::prepare(const Scene& scene) {
  const auto start = std::chrono::steady_clock::now();
  structures_.reset();
  tables_ = std::make_unique<TriangleBuffers>(*context_, scene,
                                              VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR |
                                                  VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT);
  structures_ = std::make_unique<AccelerationStructures>(*context_, *functions_, scene, *tables_);
  StructureStats stats;
  stats.build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  stats.bytes = structures_->bytes();
  stats_ = stats;
  std::vector<KernelBinding> bindings = tables_->bindings();
  KernelBinding structure{11, VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR};
  structure.acceleration_structure = structures_->top_level();
  bindings.push_back(structure);
  runner_->set_scene(scene, bindings);
}

BackendInfo vk_rt_backend() {
  return {.name = "vk-rt", .kind = BackendKind::DriverRt,
          .summary = "the driver's own ray tracing (VK_KHR_ray_tracing_pipeline)",
          .create = factory<VkRtRenderer>()};
}

}  // namespace sdfbench
