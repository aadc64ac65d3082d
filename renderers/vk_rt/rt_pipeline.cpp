#include "renderers/vk_rt/rt_pipeline.h"

#include <map>
#include <memory>

#include "renderers/vulkan/compute_kernel.h"
#include "renderers/vulkan/shader_compiler.h"
#include "renderers/vulkan/vk_error.h"

namespace sdfbench {
namespace {

constexpr VkShaderStageFlags kRaygen = VK_SHADER_STAGE_RAYGEN_BIT_KHR;


}  // namespace

RayTracingKernel::RayTracingKernel(const VulkanContext& context, const RayTracingFunctions& functions,
                                   const std::vector<uint32_t>& raygen, const std::vector<uint32_t>& miss,
                                   const std::vector<uint32_t>& closest_hit, const std::vector<KernelBinding>& bindings)
    : context_(context), rt_(functions), descriptors_(context, bindings, kRaygen) {
  VkDevice device = context.device();
  std::vector<VkShaderModule> modules;
  try {
    const VkDescriptorSetLayout set_layout = descriptors_.layout();
    const VkPushConstantRange range{kRaygen, 0, static_cast<uint32_t>(sizeof(glm::uvec4))};
    VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layout_info.setLayoutCount = 1;
    layout_info.pSetLayouts = &set_layout;
    layout_info.pushConstantRangeCount = 1;
    layout_info.pPushConstantRanges = &range;
    vk_check(vkCreatePipelineLayout(device, &layout_info, nullptr, &pipeline_layout_), "vkCreatePipelineLayout");

    // Stages 0-2; groups: ray generation, miss, the triangle hit group (closest hit only: opaque).
    const std::vector<const std::vector<uint32_t>*> code = {&raygen, &miss, &closest_hit};
    const VkShaderStageFlagBits kinds[] = {VK_SHADER_STAGE_RAYGEN_BIT_KHR, VK_SHADER_STAGE_MISS_BIT_KHR,
                                           VK_SHADER_STAGE_CLOSEST_HIT_BIT_KHR};
    std::vector<VkPipelineShaderStageCreateInfo> stages;
    for (size_t i = 0; i < code.size(); ++i) {
      modules.push_back(create_shader_module(device, *code[i]));
      VkPipelineShaderStageCreateInfo stage{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
      stage.stage = kinds[i];
      stage.module = modules.back();
      stage.pName = "main";
      stages.push_back(stage);
    }
    std::vector<VkRayTracingShaderGroupCreateInfoKHR> groups(3, {VK_STRUCTURE_TYPE_RAY_TRACING_SHADER_GROUP_CREATE_INFO_KHR});
    for (VkRayTracingShaderGroupCreateInfoKHR& g : groups)
      g.generalShader = g.closestHitShader = g.anyHitShader = g.intersectionShader = VK_SHADER_UNUSED_KHR;
    groups[0].type = groups[1].type = VK_RAY_TRACING_SHADER_GROUP_TYPE_GENERAL_KHR;
    groups[0].generalShader = 0;
    groups[1].generalShader = 1;
    groups[2].type = VK_RAY_TRACING_SHADER_GROUP_TYPE_TRIANGLES_HIT_GROUP_KHR;
    groups[2].closestHitShader = 2;
    VkRayTracingPipelineCreateInfoKHR info{VK_STRUCTURE_TYPE_RAY_TRACING_PIPELINE_CREATE_INFO_KHR};
    info.stageCount = static_cast<uint32_t>(stages.size());
    info.pStages = stages.data();
    info.groupCount = static_cast<uint32_t>(groups.size());
    info.pGroups = groups.data();
    info.maxPipelineRayRecursionDepth = 1;  // only ray generation traces rays
    info.layout = pipeline_layout_;
    vk_check(rt_.create_ray_tracing_pipelines(device, VK_NULL_HANDLE, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline_),
             "vkCreateRayTracingPipelinesKHR");
    for (VkShaderModule m : modules) vkDestroyShaderModule(device, m, nullptr);
    modules.clear();
    build_binding_table();
  } catch (...) {
    for (VkShaderModule m : modules) vkDestroyShaderModule(device, m, nullptr);
    release();
    throw;
  }
}

RayTracingKernel::~RayTracingKernel() { release(); }

void RayTracingKernel::release() {
  VkDevice device = context_.device();
  if (pipeline_) vkDestroyPipeline(device, pipeline_, nullptr);
  if (pipeline_layout_) vkDestroyPipelineLayout(device, pipeline_layout_, nullptr);
  pipeline_ = VK_NULL_HANDLE;
  pipeline_layout_ = VK_NULL_HANDLE;
}

void RayTracingKernel::build_binding_table() {
  VkPhysicalDeviceRayTracingPipelinePropertiesKHR props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_PIPELINE_PROPERTIES_KHR};
  VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  properties.pNext = &props;
  vkGetPhysicalDeviceProperties2(context_.physical_device(), &properties);
  const uint32_t handle_size = props.shaderGroupHandleSize;
  const VkDeviceSize record = align_up(handle_size, props.shaderGroupHandleAlignment);
  // Each region starts at a multiple of shaderGroupBaseAlignment; one record per region.
  const VkDeviceSize base = props.shaderGroupBaseAlignment;
  const VkDeviceSize region = align_up(record, base);
  std::vector<uint8_t> handles(3 * handle_size);
  vk_check(rt_.get_shader_group_handles(context_.device(), pipeline_, 0, 3, handles.size(), handles.data()),
           "vkGetRayTracingShaderGroupHandlesKHR");
  binding_table_ = GpuBuffer(context_, 3 * region + base,
                             VK_BUFFER_USAGE_SHADER_BINDING_TABLE_BIT_KHR | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
                             GpuBuffer::Use::Upload, "shader binding table");
  const VkDeviceAddress start = binding_table_.device_address();
  const VkDeviceAddress first = align_up(start, base);  // the buffer's own alignment may be smaller
  for (uint32_t g = 0; g < 3; ++g)
    binding_table_.write(handles.data() + g * handle_size, handle_size, (first - start) + g * region);
  raygen_region_ = {first, region, region};  // ray generation: size == stride
  miss_region_ = {first + region, record, record};
  hit_region_ = {first + 2 * region, record, record};
}

void RayTracingKernel::bind(VkCommandBuffer cmd) const {
  const VkDescriptorSet set = descriptors_.set();
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, pipeline_);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, pipeline_layout_, 0, 1, &set, 0, nullptr);
}

void RayTracingKernel::launch(VkCommandBuffer cmd, const glm::uvec4& tile, uint32_t width, uint32_t height) const {
  vkCmdPushConstants(cmd, pipeline_layout_, kRaygen, 0, sizeof(tile), &tile);
  rt_.cmd_trace_rays(cmd, &raygen_region_, &miss_region_, &hit_region_, &callable_region_, width, height, 1);
}

TileKernelFactory ray_tracing_tile_kernels(const VulkanContext& context, const RayTracingFunctions& functions) {
  auto raygen = std::make_shared<std::map<std::string, std::vector<uint32_t>>>();
  auto miss = std::make_shared<std::vector<uint32_t>>(), hit = std::make_shared<std::vector<uint32_t>>();
  return [&context, &functions, raygen, miss, hit](const std::string& defines, const std::vector<KernelBinding>& bindings) {
    std::vector<uint32_t>& generation = (*raygen)[defines];
    if (generation.empty()) generation = compile_shader("vk_rt.rgen", defines);
    if (miss->empty()) *miss = compile_shader("vk_rt.rmiss");
    if (hit->empty()) *hit = compile_shader("vk_rt.rchit");
    return std::make_unique<RayTracingKernel>(context, functions, generation, *miss, *hit, bindings);
  };
}

}  // namespace sdfbench
