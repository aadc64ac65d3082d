#include "renderers/vulkan/gpu_buffer.h"

#include <cstring>
#include <utility>

#include "renderers/vulkan/vk_error.h"
#include "util/error.h"

namespace sdfbench {
namespace {

void check_limit(const char* what, VkDeviceSize bytes, VkDeviceSize limit, const char* limit_name,
                 const std::string& device) {
  if (bytes > limit)
    throw Error(std::string("the ") + what + " needs " + std::to_string(bytes) + " bytes, more than " + limit_name +
                " (" + std::to_string(limit) + ") of Vulkan device '" + device + "'");
}

}  // namespace

GpuBuffer::GpuBuffer(const VulkanContext& context, VkDeviceSize bytes, VkBufferUsageFlags usage, Use use,
                     const char* what)
    : context_(&context), size_(std::max<VkDeviceSize>(bytes, 16)), what_(what) {
  const VkPhysicalDeviceLimits& limits = context.properties().limits;
  const std::string& device = context.info().name;
  // A buffer the device reads by address (acceleration-structure scratch) is bound through no descriptor.
  if ((usage & VK_BUFFER_USAGE_STORAGE_BUFFER_BIT) && !(usage & VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT))
    check_limit(what, size_, limits.maxStorageBufferRange, "maxStorageBufferRange", device);
  if (usage & VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT)
    check_limit(what, size_, limits.maxUniformBufferRange, "maxUniformBufferRange", device);

  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = size_;
  info.usage = usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  vk_check(vkCreateBuffer(context.device(), &info, nullptr, &buffer_), "vkCreateBuffer");
  try {
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(context.device(), buffer_, &req);
    const VkMemoryPropertyFlags required =
        use == Use::DeviceOnly ? 0 : VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    const VkMemoryPropertyFlags preferred =
        use == Use::Readback ? VK_MEMORY_PROPERTY_HOST_CACHED_BIT : VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    VkMemoryAllocateFlagsInfo flags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
    flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
    if (usage & VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT) alloc.pNext = &flags;
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = context.find_memory_type(req.memoryTypeBits, required, preferred);
    const VkResult result = vkAllocateMemory(context.device(), &alloc, nullptr, &memory_);
    if (result == VK_ERROR_OUT_OF_DEVICE_MEMORY || result == VK_ERROR_OUT_OF_HOST_MEMORY)
      throw Error(std::string("out of memory allocating the ") + what + " (" + std::to_string(req.size) + " bytes)");
    vk_check(result, "vkAllocateMemory");
    vk_check(vkBindBufferMemory(context.device(), buffer_, memory_, 0), "vkBindBufferMemory");
    if (use != Use::DeviceOnly)
      vk_check(vkMapMemory(context.device(), memory_, 0, VK_WHOLE_SIZE, 0, &mapped_), "vkMapMemory");
  } catch (...) {
    release();
    throw;
  }
}

GpuBuffer::~GpuBuffer() { release(); }

GpuBuffer::GpuBuffer(GpuBuffer&& other) noexcept { *this = std::move(other); }

GpuBuffer& GpuBuffer::operator=(GpuBuffer&& other) noexcept {
  if (this != &other) {
    release();
    context_ = std::exchange(other.context_, nullptr);
    buffer_ = std::exchange(other.buffer_, VK_NULL_HANDLE);
    memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
    view_ = std::exchange(other.view_, VK_NULL_HANDLE);
    size_ = std::exchange(other.size_, 0);
    mapped_ = std::exchange(other.mapped_, nullptr);
    what_ = other.what_;
  }
  return *this;
}

void GpuBuffer::release() {
  if (!context_) return;
  VkDevice device = context_->device();
  if (view_) vkDestroyBufferView(device, view_, nullptr);
  if (buffer_) vkDestroyBuffer(device, buffer_, nullptr);
  if (memory_) vkFreeMemory(device, memory_, nullptr);  // also unmaps
  view_ = VK_NULL_HANDLE;
  buffer_ = VK_NULL_HANDLE;
  memory_ = VK_NULL_HANDLE;
  mapped_ = nullptr;
  context_ = nullptr;
}

void GpuBuffer::write(const void* data, size_t bytes, size_t offset) {
  if (!mapped_) throw Error(std::string("internal: the ") + what_ + " is not host-visible");
  if (offset + bytes > size_) throw Error(std::string("internal: write past the end of the ") + what_);
  std::memcpy(static_cast<char*>(mapped_) + offset, data, bytes);
}

void GpuBuffer::read(void* data, size_t bytes, size_t offset) const {
  if (!mapped_) throw Error(std::string("internal: the ") + what_ + " is not host-visible");
  if (offset + bytes > size_) throw Error(std::string("internal: read past the end of the ") + what_);
  std::memcpy(data, static_cast<const char*>(mapped_) + offset, bytes);
}

VkDeviceAddress GpuBuffer::device_address() const {
  VkBufferDeviceAddressInfo info{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
  info.buffer = buffer_;
  return vkGetBufferDeviceAddress(context_->device(), &info);
}

VkBufferView GpuBuffer::texel_view(VkFormat format, size_t texel_bytes) {
  const VkDeviceSize texels = size_ / texel_bytes;
  check_limit(what_, texels, context_->properties().limits.maxTexelBufferElements, "maxTexelBufferElements (texels)",
              context_->info().name);
  if (view_) vkDestroyBufferView(context_->device(), view_, nullptr);
  VkBufferViewCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
  info.buffer = buffer_;
  info.format = format;
  info.offset = 0;
  info.range = texels * texel_bytes;
  vk_check(vkCreateBufferView(context_->device(), &info, nullptr, &view_), "vkCreateBufferView");
  return view_;
}

}  // namespace sdfbench
