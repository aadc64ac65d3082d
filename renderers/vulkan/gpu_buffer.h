#pragma once
// A Vulkan buffer with persistently mapped host-visible memory (on lavapipe all memory is
// host memory; on GPUs, device-local + host-visible is preferred where the driver offers it), or
// device-only memory the host never touches (acceleration structures and their scratch).
#include <cstddef>

#include <vulkan/vulkan.h>

#include "renderers/vulkan/vulkan_context.h"

namespace sdfbench {

// `value` rounded up to a multiple of `alignment` (buffer offsets, device addresses).
inline VkDeviceSize align_up(VkDeviceSize value, VkDeviceSize alignment) {
  return (value + alignment - 1) / alignment * alignment;
}

class GpuBuffer {
 public:
  enum class Use { Upload, Readback, DeviceOnly };

  GpuBuffer() = default;
  // Throws Error when `bytes` exceeds the device's limit for the usage (maxStorageBufferRange,
  // maxTexelBufferElements, maxUniformBufferRange), naming what and how much.
  GpuBuffer(const VulkanContext& context, VkDeviceSize bytes, VkBufferUsageFlags usage, Use use, const char* what);
  ~GpuBuffer();
  GpuBuffer(GpuBuffer&& other) noexcept;
  GpuBuffer& operator=(GpuBuffer&& other) noexcept;
  GpuBuffer(const GpuBuffer&) = delete;
  GpuBuffer& operator=(const GpuBuffer&) = delete;

  void write(const void* data, size_t bytes, size_t offset = 0);
  void read(void* data, size_t bytes, size_t offset = 0) const;
  // The buffer's device address; needs VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT.
  VkDeviceAddress device_address() const;
  // A texel view (for textureBuffer / utextureBuffer) of the whole buffer.
  VkBufferView texel_view(VkFormat format, size_t texel_bytes);

  VkBuffer handle() const { return buffer_; }
  VkDeviceSize size() const { return size_; }
  VkBufferView view() const { return view_; }

 private:
  void release();

  const VulkanContext* context_ = nullptr;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkBufferView view_ = VK_NULL_HANDLE;
  VkDeviceSize size_ = 0;
  void* mapped_ = nullptr;
  const char* what_ = "";
};

}  // namespace sdfbench
