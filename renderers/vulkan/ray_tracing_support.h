#pragma once
// Whether a device can run the vk-rt backend: the ray-tracing pipeline extensions and the
// features they need. SDFBENCH_VULKAN_HIDE_EXTENSIONS (comma-separated names) hides extensions
// from this check, so the path of a device without them can be tested on one that has them.
#include <set>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

namespace sdfbench {

struct RayTracingSupport {
  uint32_t api_version = 0;          // the device's
  std::set<std::string> extensions;  // the device's, less the hidden ones
  bool acceleration_structure = false;
  bool ray_tracing_pipeline = false;
  bool buffer_device_address = false;
};

// The device extensions vk-rt enables.
const std::vector<const char*>& ray_tracing_extensions();

RayTracingSupport query_ray_tracing_support(VkPhysicalDevice device);

// Empty when vk-rt can run, else what the device lacks, e.g. "lacks VK_KHR_ray_tracing_pipeline".
std::string ray_tracing_gap(const RayTracingSupport& support);

}  // namespace sdfbench
