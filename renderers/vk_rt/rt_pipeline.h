#pragma once
// vk-rt's ray-tracing pipeline: vk_rt.rgen (render_main.glsl as ray generation), one miss and one
// triangle hit group with vk_rt.rchit, and the shader binding table laid out with the device's
// handle size and alignments. A TileKernel: VulkanFrameRunner launches it like a compute kernel.
#include <vector>

#include "renderers/vk_rt/rt_functions.h"
#include "renderers/vulkan/descriptor_set.h"
#include "renderers/vulkan/gpu_buffer.h"
#include "renderers/vulkan/tile_kernel.h"

namespace sdfbench {

class RayTracingKernel : public TileKernel {
 public:
  RayTracingKernel(const VulkanContext& context, const RayTracingFunctions& functions,
                   const std::vector<uint32_t>& raygen, const std::vector<uint32_t>& miss,
                   const std::vector<uint32_t>& closest_hit, const std::vector<KernelBinding>& bindings);
  ~RayTracingKernel() override;
  RayTracingKernel(const RayTracingKernel&) = delete;
  RayTracingKernel& operator=(const RayTracingKernel&) = delete;

  void bind(VkCommandBuffer cmd) const override;
  void launch(VkCommandBuffer cmd, const glm::uvec4& tile, uint32_t width, uint32_t height) const override;
  VkPipelineStageFlags stage() const override { return VK_PIPELINE_STAGE_RAY_TRACING_SHADER_BIT_KHR; }

 private:
  void release();
  void build_binding_table();

  const VulkanContext& context_;
  const RayTracingFunctions& rt_;
  DescriptorSet descriptors_;
  VkPipelineLayout pipeline_layout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  GpuBuffer binding_table_;
  VkStridedDeviceAddressRegionKHR raygen_region_{}, miss_region_{}, hit_region_{}, callable_region_{};
};

// The kernels of vk_rt.rgen: its SPIR-V compiled once per set of defines (the miss and
// closest-hit shaders once).
TileKernelFactory ray_tracing_tile_kernels(const VulkanContext& context, const RayTracingFunctions& functions);

}  // namespace sdfbench
