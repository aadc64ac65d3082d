#include "renderers/vk_rt/vk_rt_renderer.h"

#include <chrono>

#include "renderers/backend_registry.h"
#include "renderers/vk_rt/rt_pipeline.h"
#include "util/error.h"

namespace sdfbench {

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
  return {.name = "vk-rt", .kind = "driver-rt",
          .summary = "the driver's own ray tracing (VK_KHR_ray_tracing_pipeline)",
          .create = factory<VkRtRenderer>()};
}

}  // namespace sdfbench
