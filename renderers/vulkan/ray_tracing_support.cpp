#include "renderers/vulkan/ray_tracing_support.h"

#include <cstdlib>
#include <sstream>

namespace sdfbench {

const std::vector<const char*>& ray_tracing_extensions() {
  static const std::vector<const char*> names = {VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME,
                                                 VK_KHR_RAY_TRACING_PIPELINE_EXTENSION_NAME,
                                                 VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME};
  return names;
}

RayTracingSupport query_ray_tracing_support(VkPhysicalDevice device) {
  RayTracingSupport support;
  VkPhysicalDeviceProperties properties;
  vkGetPhysicalDeviceProperties(device, &properties);
  support.api_version = properties.apiVersion;
  uint32_t count = 0;
  vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr);
  std::vector<VkExtensionProperties> available(count);
  vkEnumerateDeviceExtensionProperties(device, nullptr, &count, available.data());
  for (const VkExtensionProperties& e : available) support.extensions.insert(e.extensionName);
  if (const char* hidden = std::getenv("SDFBENCH_VULKAN_HIDE_EXTENSIONS")) {
    std::istringstream names(hidden);
    for (std::string name; std::getline(names, name, ',');) support.extensions.erase(name);
  }
  if (support.api_version < VK_API_VERSION_1_2) return support;  // bufferDeviceAddress is core from 1.2

  // Feature structures only for extensions the device has (a chain may not name others).
  VkPhysicalDeviceBufferDeviceAddressFeatures address{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_BUFFER_DEVICE_ADDRESS_FEATURES};
  VkPhysicalDeviceAccelerationStructureFeaturesKHR structures{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR};
  VkPhysicalDeviceRayTracingPipelineFeaturesKHR pipeline{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_PIPELINE_FEATURES_KHR};
  VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  features.pNext = &address;
  void** tail = &address.pNext;
  if (support.extensions.count(VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME)) {
    *tail = &structures;
    tail = &structures.pNext;
  }
  if (support.extensions.count(VK_KHR_RAY_TRACING_PIPELINE_EXTENSION_NAME)) *tail = &pipeline;
  vkGetPhysicalDeviceFeatures2(device, &features);
  support.buffer_device_address = address.bufferDeviceAddress;
  support.acceleration_structure = structures.accelerationStructure;
  support.ray_tracing_pipeline = pipeline.rayTracingPipeline;
  return support;
}

std::string ray_tracing_gap(const RayTracingSupport& support) {
  // The pipeline extension first: it is what a device without ray tracing is missing.
  const std::vector<const char*> order = {VK_KHR_RAY_TRACING_PIPELINE_EXTENSION_NAME,
                                          VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME,
                                          VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME};
  for (const char* name : order)
    if (!support.extensions.count(name)) return std::string("lacks ") + name;
  if (support.api_version < VK_API_VERSION_1_2) return "lacks Vulkan 1.2 (bufferDeviceAddress)";
  if (!support.buffer_device_address) return "lacks the bufferDeviceAddress feature";
  if (!support.acceleration_structure) return "lacks the accelerationStructure feature";
  if (!support.ray_tracing_pipeline) return "lacks the rayTracingPipeline feature";
  return "";
}

}  // namespace sdfbench
