#pragma once
// A compute pipeline with one descriptor set, built from a list of bound buffers.
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "renderers/vulkan/descriptor_set.h"
#include "renderers/vulkan/vulkan_context.h"

namespace sdfbench {

// A shader module of `spirv`; the caller destroys it once its pipeline exists.
VkShaderModule create_shader_module(VkDevice device, const std::vector<uint32_t>& spirv);

class ComputeKernel {
 public:
  ComputeKernel(const VulkanContext& context, const std::vector<uint32_t>& spirv,
                const std::vector<KernelBinding>& bindings, uint32_t push_constant_bytes);
  ~ComputeKernel();
  ComputeKernel(const ComputeKernel&) = delete;
  ComputeKernel& operator=(const ComputeKernel&) = delete;

  void bind(VkCommandBuffer cmd) const;
  void push(VkCommandBuffer cmd, const void* data, uint32_t bytes) const;

 private:
  void release();

  const VulkanContext& context_;
  DescriptorSet descriptors_;
  VkPipelineLayout pipeline_layout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
};

}  // namespace sdfbench
