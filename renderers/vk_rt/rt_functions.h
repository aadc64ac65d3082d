#pragma once
// The entry points of VK_KHR_acceleration_structure and VK_KHR_ray_tracing_pipeline: the loader
// does not export extension functions, so they come from vkGetDeviceProcAddr.
#include <vulkan/vulkan.h>

#include "renderers/vulkan/vulkan_context.h"

namespace sdfbench {

struct RayTracingFunctions {
  // Throws Error naming the first entry point the driver does not return.
  explicit RayTracingFunctions(const VulkanContext& context);

  PFN_vkCreateAccelerationStructureKHR create_acceleration_structure;
  PFN_vkDestroyAccelerationStructureKHR destroy_acceleration_structure;
  PFN_vkGetAccelerationStructureBuildSizesKHR get_build_sizes;
  PFN_vkGetAccelerationStructureDeviceAddressKHR get_acceleration_structure_address;
  PFN_vkCmdBuildAccelerationStructuresKHR cmd_build_acceleration_structures;
  PFN_vkCmdWriteAccelerationStructuresPropertiesKHR cmd_write_properties;
  PFN_vkCmdCopyAccelerationStructureKHR cmd_copy_acceleration_structure;
  PFN_vkCreateRayTracingPipelinesKHR create_ray_tracing_pipelines;
  PFN_vkGetRayTracingShaderGroupHandlesKHR get_shader_group_handles;
  PFN_vkCmdTraceRaysKHR cmd_trace_rays;
};

}  // namespace sdfbench
