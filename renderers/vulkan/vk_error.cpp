#include "renderers/vulkan/vk_error.h"

#include <vulkan/vulkan.hpp>
#include <vulkan/vulkan_to_string.hpp>

#include "util/error.h"


namespace sdfbench {

std::string vk_result_name(VkResult result) {
  return "VK_" + vk::to_string(static_cast<vk::Result>(result)) + " (" + std::to_string(static_cast<int>(result)) + ")";
}

void vk_check(VkResult result, const char* what) {
  if (result != VK_SUCCESS) throw Error(std::string("Vulkan: ") + what + " failed: " + vk_result_name(result));
}

}  // namespace sdfbench
