#pragma once
#include <memory>

#include "renderers/renderer.h"
#include "renderers/vk_rt/acceleration_structures.h"
#include "renderers/vk_rt/rt_functions.h"
#include "renderers/vulkan/triangle_buffers.h"
#include "renderers/vulkan/vulkan_context.h"
#include "renderers/vulkan/vulkan_frame_runner.h"

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

// Its entry in the backend registry (renderers/backend_registry.h).
struct BackendInfo;
BackendInfo vk_rt_backend();

}  // namespace sdfbench
