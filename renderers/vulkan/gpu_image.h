#pragma once
// A read-only 3D image sampled with trilinear filtering (sdf-bricks' atlas with --brick-fetch
// sampler): uploaded once through a staging buffer, then in SHADER_READ_ONLY_OPTIMAL layout,
// with its view and a linear, clamp-to-edge sampler.
#include <cstddef>

#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

#include "renderers/vulkan/vulkan_context.h"

namespace sdfbench {

class GpuImage3D {
 public:
  GpuImage3D() = default;
  // `texels`: extent.x * extent.y * extent.z texels of `texel_bytes`, x fastest. Throws Error when
  // the extent passes maxImageDimension3D or the device cannot filter `format` linearly.
  GpuImage3D(const VulkanContext& context, glm::uvec3 extent, VkFormat format, size_t texel_bytes, const void* texels,
             const char* what);
  ~GpuImage3D();
  GpuImage3D(GpuImage3D&& other) noexcept;
  GpuImage3D& operator=(GpuImage3D&& other) noexcept;
  GpuImage3D(const GpuImage3D&) = delete;
  GpuImage3D& operator=(const GpuImage3D&) = delete;

  VkImageView view() const { return view_; }
  VkSampler sampler() const { return sampler_; }

 private:
  void release();
  const VulkanContext* context_ = nullptr;
  VkImage image_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkImageView view_ = VK_NULL_HANDLE;
  VkSampler sampler_ = VK_NULL_HANDLE;
};

}  // namespace sdfbench
