#include "renderers/vulkan/gpu_image.h"

#include <string>
#include <utility>

#include "renderers/vulkan/gpu_buffer.h"
#include "renderers/vulkan/one_time_commands.h"
#include "renderers/vulkan/vk_error.h"
#include "util/error.h"

namespace sdfbench {

GpuImage3D::GpuImage3D(const VulkanContext& context, glm::uvec3 extent, VkFormat format, size_t texel_bytes,
                       const void* texels, const char* what)
    : context_(&context) {
  const uint32_t limit = context.properties().limits.maxImageDimension3D;
  if (extent.x > limit || extent.y > limit || extent.z > limit)
    throw Error(std::string("the ") + what + " needs a 3D image of " + std::to_string(extent.x) + "x" + std::to_string(extent.y) +
                "x" + std::to_string(extent.z) + " texels, more than maxImageDimension3D (" + std::to_string(limit) +
                ") of Vulkan device '" + context.info().name + "'");
  VkFormatProperties properties;
  vkGetPhysicalDeviceFormatProperties(context.physical_device(), format, &properties);
  if (!(properties.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT))
    throw Error(std::string("Vulkan device '") + context.info().name + "' cannot filter the " + what +
                "'s format linearly; use --brick-fetch texel");
  VkDevice device = context.device();
  try {
    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.imageType = VK_IMAGE_TYPE_3D;
    info.format = format;
    info.extent = {extent.x, extent.y, extent.z};
    info.mipLevels = 1;
    info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    vk_check(vkCreateImage(device, &info, nullptr, &image_), "vkCreateImage");
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(device, image_, &req);
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = context.find_memory_type(req.memoryTypeBits, 0, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    const VkResult result = vkAllocateMemory(device, &alloc, nullptr, &memory_);
    if (result == VK_ERROR_OUT_OF_DEVICE_MEMORY || result == VK_ERROR_OUT_OF_HOST_MEMORY)
      throw Error(std::string("out of memory allocating the ") + what + " (" + std::to_string(req.size) + " bytes)");
    vk_check(result, "vkAllocateMemory");
    vk_check(vkBindImageMemory(device, image_, memory_, 0), "vkBindImageMemory");

    const size_t bytes = size_t(extent.x) * extent.y * extent.z * texel_bytes;
    GpuBuffer staging(context, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, GpuBuffer::Use::Upload, what);
    staging.write(texels, bytes);
    run_one_time_commands(context, [&](VkCommandBuffer commands) {
      VkImageMemoryBarrier barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
      barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
      barrier.image = image_;
      barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
      barrier.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
      barrier.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
      barrier.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
      vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0,
                           nullptr, 1, &barrier);
      VkBufferImageCopy copy{};
      copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
      copy.imageExtent = {extent.x, extent.y, extent.z};
      vkCmdCopyBufferToImage(commands, staging.handle(), image_, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
      barrier.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
      barrier.newLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
      barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
      barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
      vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0, nullptr,
                           0, nullptr, 1, &barrier);
    });

    VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    view.image = image_;
    view.viewType = VK_IMAGE_VIEW_TYPE_3D;
    view.format = format;
    view.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vk_check(vkCreateImageView(device, &view, nullptr, &view_), "vkCreateImageView");
    VkSamplerCreateInfo sampler{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    sampler.magFilter = sampler.minFilter = VK_FILTER_LINEAR;
    sampler.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    sampler.addressModeU = sampler.addressModeV = sampler.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    sampler.maxLod = 0.0f;
    vk_check(vkCreateSampler(device, &sampler, nullptr, &sampler_), "vkCreateSampler");
  } catch (...) {
    release();
    throw;
  }
}

GpuImage3D::~GpuImage3D() { release(); }

GpuImage3D::GpuImage3D(GpuImage3D&& other) noexcept { *this = std::move(other); }

GpuImage3D& GpuImage3D::operator=(GpuImage3D&& other) noexcept {
  if (this != &other) {
    release();
    context_ = std::exchange(other.context_, nullptr);
    image_ = std::exchange(other.image_, VK_NULL_HANDLE);
    memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
    view_ = std::exchange(other.view_, VK_NULL_HANDLE);
    sampler_ = std::exchange(other.sampler_, VK_NULL_HANDLE);
  }
  return *this;
}

void GpuImage3D::release() {
  if (!context_) return;
  VkDevice device = context_->device();
  if (sampler_) vkDestroySampler(device, sampler_, nullptr);
  if (view_) vkDestroyImageView(device, view_, nullptr);
  if (image_) vkDestroyImage(device, image_, nullptr);
  if (memory_) vkFreeMemory(device, memory_, nullptr);
  sampler_ = VK_NULL_HANDLE;
  view_ = VK_NULL_HANDLE;
  image_ = VK_NULL_HANDLE;
  memory_ = VK_NULL_HANDLE;
  context_ = nullptr;
}

}  // namespace sdfbench
