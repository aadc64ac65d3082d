#include "renderers/vulkan/loop_cap_probe.h"

#include "renderers/vulkan/compute_kernel.h"
#include "renderers/vulkan/gpu_buffer.h"
#include "renderers/vulkan/shader_compiler.h"
#include "renderers/vulkan/vk_error.h"

namespace sdfbench {

bool has_loop_cap(const VulkanContext& context) {
  static const std::vector<uint32_t> spirv = compile_compute_shader("loop_cap_probe.comp");
  VkDevice device = context.device();
  GpuBuffer result(context, sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, GpuBuffer::Use::Readback,
                   "loop-cap probe result");
  const uint32_t zero = 0;
  result.write(&zero, sizeof(zero));
  ComputeKernel kernel(context, spirv, {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &result}}, sizeof(uint32_t));

  VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  alloc.commandPool = context.command_pool();
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  vk_check(vkAllocateCommandBuffers(device, &alloc, &cmd), "vkAllocateCommandBuffers");
  VkFence fence = VK_NULL_HANDLE;
  try {
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vk_check(vkBeginCommandBuffer(cmd, &begin), "vkBeginCommandBuffer");
    kernel.bind(cmd);
    kernel.push(cmd, &kLoopCapProbeTrips, sizeof(kLoopCapProbeTrips));
    vkCmdDispatch(cmd, 1, 1, 1);
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &barrier, 0,
                         nullptr, 0, nullptr);
    vk_check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
    VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    vk_check(vkCreateFence(device, &fence_info, nullptr, &fence), "vkCreateFence");
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    vk_check(vkQueueSubmit(context.queue(), 1, &submit, fence), "vkQueueSubmit");
    vk_check(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  } catch (...) {
    if (fence) vkDestroyFence(device, fence, nullptr);
    vkFreeCommandBuffers(device, context.command_pool(), 1, &cmd);
    throw;
  }
  vkDestroyFence(device, fence, nullptr);
  vkFreeCommandBuffers(device, context.command_pool(), 1, &cmd);
  uint32_t done = 0;
  result.read(&done, sizeof(done));
  return done != kLoopCapProbeTrips;
}

}  // namespace sdfbench
