#pragma once
#include <string>

#include <vulkan/vulkan.h>

namespace sdfbench {

std::string vk_result_name(VkResult result);

// Throws Error("Vulkan: <what> failed: VK_ERROR_...") unless result is VK_SUCCESS.
void vk_check(VkResult result, const char* what);

}  // namespace sdfbench
