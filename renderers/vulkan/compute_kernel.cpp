#include "renderers/vulkan/compute_kernel.h"

#include "renderers/vulkan/vk_error.h"

namespace sdfbench {

VkShaderModule create_shader_module(VkDevice device, const std::vector<uint32_t>& spirv) {
  VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  info.codeSize = spirv.size() * sizeof(uint32_t);
  info.pCode = spirv.data();
  VkShaderModule module = VK_NULL_HANDLE;
  vk_check(vkCreateShaderModule(device, &info, nullptr, &module), "vkCreateShaderModule");
  return module;
}

ComputeKernel::ComputeKernel(const VulkanContext& context, const std::vector<uint32_t>& spirv,
                             const std::vector<KernelBinding>& bindings, uint32_t push_constant_bytes)
    : context_(context), descriptors_(context, bindings, VK_SHADER_STAGE_COMPUTE_BIT) {
  VkDevice device = context.device();
  try {
    const VkDescriptorSetLayout set_layout = descriptors_.layout();
    VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, push_constant_bytes};
    VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layout_info.setLayoutCount = 1;
    layout_info.pSetLayouts = &set_layout;
    layout_info.pushConstantRangeCount = push_constant_bytes ? 1 : 0;
    layout_info.pPushConstantRanges = &range;
    vk_check(vkCreatePipelineLayout(device, &layout_info, nullptr, &pipeline_layout_), "vkCreatePipelineLayout");

    VkShaderModule module = create_shader_module(device, spirv);
    VkComputePipelineCreateInfo pipeline_info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    pipeline_info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    pipeline_info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    pipeline_info.stage.module = module;
    pipeline_info.stage.pName = "main";
    pipeline_info.layout = pipeline_layout_;
    const VkResult result = vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &pipeline_info, nullptr, &pipeline_);
    vkDestroyShaderModule(device, module, nullptr);
    vk_check(result, "vkCreateComputePipelines");
  } catch (...) {
    release();
    throw;
  }
}

ComputeKernel::~ComputeKernel() { release(); }

void ComputeKernel::release() {
  VkDevice device = context_.device();
  if (pipeline_) vkDestroyPipeline(device, pipeline_, nullptr);
  if (pipeline_layout_) vkDestroyPipelineLayout(device, pipeline_layout_, nullptr);
  pipeline_ = VK_NULL_HANDLE;
  pipeline_layout_ = VK_NULL_HANDLE;
}

void ComputeKernel::bind(VkCommandBuffer cmd) const {
  const VkDescriptorSet set = descriptors_.set();
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_layout_, 0, 1, &set, 0, nullptr);
}

void ComputeKernel::push(VkCommandBuffer cmd, const void* data, uint32_t bytes) const {
  vkCmdPushConstants(cmd, pipeline_layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, bytes, data);
}

}  // namespace sdfbench
