#pragma once
// Records commands into a fresh command buffer, submits it and waits: for work done once
// (probes, acceleration-structure builds), not for frames (VulkanFrameRunner keeps its own).
#include <functional>

#include <vulkan/vulkan.h>

#include "renderers/vulkan/vulkan_context.h"

namespace sdfbench {

void run_one_time_commands(const VulkanContext& context, const std::function<void(VkCommandBuffer)>& record);

}  // namespace sdfbench
