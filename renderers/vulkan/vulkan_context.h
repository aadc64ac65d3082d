#pragma once
// Instance, device and queue for compute (docs/design.md, "Backends": lavapipe by default, --device picks another).
#include <atomic>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

namespace sdfbench {

struct VulkanDeviceInfo {
  uint32_t index = 0;
  std::string name;
  std::string type;         // cpu, discrete-gpu, integrated-gpu, virtual-gpu, other
  std::string driver;       // driverName, e.g. "llvmpipe"
  std::string driver_info;  // driverInfo, e.g. "Mesa 22.3.6 (LLVM 15.0.6)"
  std::string api_version;
};

// Ticks from timestamp `begin` to `end` of a queue with `valid_bits` timestamp bits (36 or 48 on
// some GPUs, 64 on lavapipe): the difference modulo 2^valid_bits, which also survives a wrap.
inline uint64_t timestamp_ticks(uint64_t begin, uint64_t end, uint32_t valid_bits) {
  const uint64_t mask = valid_bits >= 64 ? ~uint64_t(0) : (uint64_t(1) << valid_bits) - 1;
  return (end - begin) & mask;
}

class VulkanContext {
 public:
  struct Options {
    std::string device = "lavapipe";
    bool validation = false;
    // Enable the ray-tracing pipeline extensions and bufferDeviceAddress (vk-rt); a device that
    // lacks them is an Error "device 'X' lacks ..." (ray_tracing_support.h).
    bool ray_tracing = false;
  };

  explicit VulkanContext(const Options& options);
  ~VulkanContext();
  VulkanContext(const VulkanContext&) = delete;
  VulkanContext& operator=(const VulkanContext&) = delete;

  // Every physical device the loader sees; throws Error when Vulkan itself is unusable.
  static std::vector<VulkanDeviceInfo> list_devices();

  VkDevice device() const { return device_; }
  VkPhysicalDevice physical_device() const { return physical_; }
  VkQueue queue() const { return queue_; }
  uint32_t queue_family() const { return queue_family_; }
  VkCommandPool command_pool() const { return command_pool_; }
  const VkPhysicalDeviceProperties& properties() const { return properties_; }
  const VulkanDeviceInfo& info() const { return info_; }
  bool has_timestamps() const { return timestamp_valid_bits_ > 0; }
  uint32_t timestamp_valid_bits() const { return timestamp_valid_bits_; }

  // A memory type with every `required` flag, preferring one that also has `preferred`.
  uint32_t find_memory_type(uint32_t type_bits, VkMemoryPropertyFlags required,
                            VkMemoryPropertyFlags preferred) const;

  uint32_t validation_messages() const { return validation_messages_.load(); }

 private:
  void release();  // destroys whatever handles exist (also after a failed constructor)
  static VKAPI_ATTR VkBool32 VKAPI_CALL on_validation_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                               VkDebugUtilsMessageTypeFlagsEXT type,
                                                               const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                               void* user);

  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  VkCommandPool command_pool_ = VK_NULL_HANDLE;
  uint32_t queue_family_ = 0;
  uint32_t timestamp_valid_bits_ = 0;
  VkPhysicalDeviceProperties properties_{};
  VkPhysicalDeviceMemoryProperties memory_{};
  VulkanDeviceInfo info_;
  std::atomic<uint32_t> validation_messages_{0};
};

}  // namespace sdfbench
