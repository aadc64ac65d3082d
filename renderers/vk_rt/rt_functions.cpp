#include "renderers/vk_rt/rt_functions.h"

#include <string>

#include "util/error.h"


namespace sdfbench {
namespace {

template <typename Function>
void load(VkDevice device, const char* name, Function& out) {
  out = reinterpret_cast<Function>(vkGetDeviceProcAddr(device, name));
  if (!out) throw Error(std::string("Vulkan: the driver does not provide ") + name);
}

}  // namespace

RayTracingFunctions::RayTracingFunctions(const VulkanContext& context) {
  VkDevice d = context.device();
  load(d, "vkCreateAccelerationStructureKHR", create_acceleration_structure);
  load(d, "vkDestroyAccelerationStructureKHR", destroy_acceleration_structure);
  load(d, "vkGetAccelerationStructureBuildSizesKHR", get_build_sizes);
  load(d, "vkGetAccelerationStructureDeviceAddressKHR", get_acceleration_structure_address);
  load(d, "vkCmdBuildAccelerationStructuresKHR", cmd_build_acceleration_structures);
  load(d, "vkCmdWriteAccelerationStructuresPropertiesKHR", cmd_write_properties);
  load(d, "vkCmdCopyAccelerationStructureKHR", cmd_copy_acceleration_structure);
  load(d, "vkCreateRayTracingPipelinesKHR", create_ray_tracing_pipelines);
  load(d, "vkGetRayTracingShaderGroupHandlesKHR", get_shader_group_handles);
  load(d, "vkCmdTraceRaysKHR", cmd_trace_rays);
}

}  // namespace sdfbench
