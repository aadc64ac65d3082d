#include "renderers/vulkan/loop_cap_probe.h"

#include "renderers/vulkan/compute_kernel.h"
#include "renderers/vulkan/gpu_buffer.h"
#include "renderers/vulkan/one_time_commands.h"
#include "renderers/vulkan/shader_compiler.h"

namespace sdfbench {

bool has_loop_cap(const VulkanContext& context) {
  static const std::vector<uint32_t> spirv = compile_shader("loop_cap_probe.comp");
  GpuBuffer result(context, sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, GpuBuffer::Use::Readback,
                   "loop-cap probe result");
  const uint32_t zero = 0;
  result.write(&zero, sizeof(zero));
  ComputeKernel kernel(context, spirv, {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &result}}, sizeof(uint32_t));

  run_one_time_commands(context, [&](VkCommandBuffer cmd) {
    kernel.bind(cmd);
    kernel.push(cmd, &kLoopCapProbeTrips, sizeof(kLoopCapProbeTrips));
    vkCmdDispatch(cmd, 1, 1, 1);
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &barrier, 0,
                         nullptr, 0, nullptr);
  });
  uint32_t done = 0;
  result.read(&done, sizeof(done));
  return done != kLoopCapProbeTrips;
}

}  // namespace sdfbench
