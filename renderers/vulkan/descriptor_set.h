#pragma once
// One descriptor set (and its layout and pool) holding a list of bound buffers, texel buffers or
// acceleration structures or sampled 3D images: what a compute or ray-tracing pipeline of a backend reads.
#include <vector>

#include <vulkan/vulkan.h>

#include "renderers/vulkan/gpu_buffer.h"
#include "renderers/vulkan/gpu_image.h"
#include "renderers/vulkan/vulkan_context.h"

namespace sdfbench {

struct KernelBinding {
  uint32_t binding;
  VkDescriptorType type;  // UNIFORM_BUFFER, STORAGE_BUFFER, UNIFORM_TEXEL_BUFFER, ACCELERATION_STRUCTURE_KHR or COMBINED_IMAGE_SAMPLER
  const GpuBuffer* buffer = nullptr;
  VkAccelerationStructureKHR acceleration_structure = VK_NULL_HANDLE;  // ACCELERATION_STRUCTURE_KHR only
  const GpuImage3D* image = nullptr;  // COMBINED_IMAGE_SAMPLER only
};

class DescriptorSet {
 public:
  // stages: the shader stages that see every binding.
  DescriptorSet(const VulkanContext& context, const std::vector<KernelBinding>& bindings, VkShaderStageFlags stages);
  ~DescriptorSet();
  DescriptorSet(const DescriptorSet&) = delete;
  DescriptorSet& operator=(const DescriptorSet&) = delete;

  VkDescriptorSetLayout layout() const { return layout_; }
  VkDescriptorSet set() const { return set_; }

 private:
  void release();

  const VulkanContext& context_;
  VkDescriptorSetLayout layout_ = VK_NULL_HANDLE;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
};

}  // namespace sdfbench
