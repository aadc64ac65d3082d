#include "renderers/vulkan/descriptor_set.h"

#include <map>

#include "renderers/vulkan/vk_error.h"

namespace sdfbench {

DescriptorSet::DescriptorSet(const VulkanContext& context, const std::vector<KernelBinding>& bindings,
                             VkShaderStageFlags stages)
    : context_(context) {
  VkDevice device = context.device();
  try {
    std::vector<VkDescriptorSetLayoutBinding> layout_bindings;
    std::map<VkDescriptorType, uint32_t> type_counts;
    for (const KernelBinding& b : bindings) {
      layout_bindings.push_back({b.binding, b.type, 1, stages, nullptr});
      ++type_counts[b.type];
    }
    VkDescriptorSetLayoutCreateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    set_info.bindingCount = static_cast<uint32_t>(layout_bindings.size());
    set_info.pBindings = layout_bindings.data();
    vk_check(vkCreateDescriptorSetLayout(device, &set_info, nullptr, &layout_), "vkCreateDescriptorSetLayout");

    std::vector<VkDescriptorPoolSize> sizes;
    for (const auto& [type, count] : type_counts) sizes.push_back({type, count});
    VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pool_info.maxSets = 1;
    pool_info.poolSizeCount = static_cast<uint32_t>(sizes.size());
    pool_info.pPoolSizes = sizes.data();
    vk_check(vkCreateDescriptorPool(device, &pool_info, nullptr, &pool_), "vkCreateDescriptorPool");
    VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    alloc.descriptorPool = pool_;
    alloc.descriptorSetCount = 1;
    alloc.pSetLayouts = &layout_;
    vk_check(vkAllocateDescriptorSets(device, &alloc, &set_), "vkAllocateDescriptorSets");

    // Sized up front: the writes point into these vectors.
    std::vector<VkDescriptorBufferInfo> buffer_infos(bindings.size());
    std::vector<VkBufferView> views(bindings.size());
    std::vector<VkDescriptorImageInfo> image_infos(bindings.size());
    std::vector<VkWriteDescriptorSetAccelerationStructureKHR> structures(bindings.size());
    std::vector<VkWriteDescriptorSet> writes;
    for (size_t i = 0; i < bindings.size(); ++i) {
      const KernelBinding& b = bindings[i];
      VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
      w.dstSet = set_;
      w.dstBinding = b.binding;
      w.descriptorCount = 1;
      w.descriptorType = b.type;
      if (b.type == VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR) {
        structures[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET_ACCELERATION_STRUCTURE_KHR};
        structures[i].accelerationStructureCount = 1;
        structures[i].pAccelerationStructures = &b.acceleration_structure;
        w.pNext = &structures[i];
      } else if (b.type == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER) {
        image_infos[i] = {b.image->sampler(), b.image->view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        w.pImageInfo = &image_infos[i];
      } else if (b.type == VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER) {
        views[i] = b.buffer->view();
        w.pTexelBufferView = &views[i];
      } else {
        buffer_infos[i] = {b.buffer->handle(), 0, VK_WHOLE_SIZE};
        w.pBufferInfo = &buffer_infos[i];
      }
      writes.push_back(w);
    }
    vkUpdateDescriptorSets(device, static_cast<uint32_t>(writes.size()), writes.data(), 0, nullptr);
  } catch (...) {
    release();
    throw;
  }
}

DescriptorSet::~DescriptorSet() { release(); }

void DescriptorSet::release() {
  VkDevice device = context_.device();
  if (pool_) vkDestroyDescriptorPool(device, pool_, nullptr);  // frees the set
  if (layout_) vkDestroyDescriptorSetLayout(device, layout_, nullptr);
  pool_ = VK_NULL_HANDLE;
  layout_ = VK_NULL_HANDLE;
  set_ = VK_NULL_HANDLE;
}

}  // namespace sdfbench
