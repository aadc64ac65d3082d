#include "renderers/vulkan/vulkan_context.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <iostream>

#include "renderers/vulkan/ray_tracing_support.h"
#include "renderers/vulkan/vk_error.h"
#include "util/error.h"

namespace sdfbench {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

std::string device_type_name(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete-gpu";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated-gpu";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual-gpu";
    default: return "other";
  }
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

VkInstance create_instance(bool validation) {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "sdfbench";
  app.apiVersion = VK_API_VERSION_1_2;
  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pApplicationInfo = &app;
  const char* layers[] = {kValidationLayer};
  const char* extensions[] = {VK_EXT_DEBUG_UTILS_EXTENSION_NAME};
  if (validation) {
    uint32_t count = 0;
    vkEnumerateInstanceLayerProperties(&count, nullptr);
    std::vector<VkLayerProperties> available(count);
    vkEnumerateInstanceLayerProperties(&count, available.data());
    const bool found = std::any_of(available.begin(), available.end(),
                                   [](const VkLayerProperties& l) { return std::strcmp(l.layerName, kValidationLayer) == 0; });
    if (!found)
      throw Error(std::string("validation requested but ") + kValidationLayer +
                  " is not installed (Debian: apt-get install vulkan-validationlayers)");
    info.enabledLayerCount = 1;
    info.ppEnabledLayerNames = layers;
    info.enabledExtensionCount = 1;
    info.ppEnabledExtensionNames = extensions;
  }
  VkInstance instance = VK_NULL_HANDLE;
  const VkResult result = vkCreateInstance(&info, nullptr, &instance);
  if (result == VK_ERROR_INCOMPATIBLE_DRIVER || result == VK_ERROR_INITIALIZATION_FAILED)
    throw Error("no Vulkan driver found (" + vk_result_name(result) +
                "); install Mesa's lavapipe (Debian: apt-get install mesa-vulkan-drivers)");
  vk_check(result, "vkCreateInstance");
  return instance;
}

std::vector<VkPhysicalDevice> physical_devices(VkInstance instance) {
  uint32_t count = 0;
  vk_check(vkEnumeratePhysicalDevices(instance, &count, nullptr), "vkEnumeratePhysicalDevices");
  std::vector<VkPhysicalDevice> devices(count);
  vk_check(vkEnumeratePhysicalDevices(instance, &count, devices.data()), "vkEnumeratePhysicalDevices");
  return devices;
}

VulkanDeviceInfo describe(VkPhysicalDevice device, uint32_t index) {
  VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
  VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  props.pNext = &driver;
  vkGetPhysicalDeviceProperties2(device, &props);
  VulkanDeviceInfo info;
  info.index = index;
  info.name = props.properties.deviceName;
  info.type = device_type_name(props.properties.deviceType);
  info.driver = driver.driverName;
  info.driver_info = driver.driverInfo;
  const uint32_t v = props.properties.apiVersion;
  info.api_version = std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) + "." +
                     std::to_string(VK_API_VERSION_PATCH(v));
  return info;
}

// "lavapipe"/"llvmpipe"/"cpu": the first CPU device; "gpu": the first discrete, else
// integrated GPU; digits: an index; anything else: a case-insensitive name substring.
int pick_device(const std::vector<VulkanDeviceInfo>& devices, const std::string& wanted) {
  const std::string w = lower(wanted);
  auto first = [&](auto pred) {
    for (const VulkanDeviceInfo& d : devices)
      if (pred(d)) return static_cast<int>(d.index);
    return -1;
  };
  if (w == "lavapipe" || w == "llvmpipe" || w == "cpu") return first([](const auto& d) { return d.type == "cpu"; });
  if (w == "gpu") {
    const int discrete = first([](const auto& d) { return d.type == "discrete-gpu"; });
    return discrete >= 0 ? discrete : first([](const auto& d) { return d.type == "integrated-gpu"; });
  }
  if (!w.empty() && std::all_of(w.begin(), w.end(), [](unsigned char c) { return std::isdigit(c); })) {
    const unsigned long index = std::stoul(w);
    return index < devices.size() ? static_cast<int>(index) : -1;
  }
  return first([&](const auto& d) { return lower(d.name).find(w) != std::string::npos; });
}

}  // namespace

std::vector<VulkanDeviceInfo> VulkanContext::list_devices() {
  VkInstance instance = create_instance(false);
  std::vector<VulkanDeviceInfo> result;
  try {
    const auto devices = physical_devices(instance);
    for (uint32_t i = 0; i < devices.size(); ++i) result.push_back(describe(devices[i], i));
  } catch (...) {
    vkDestroyInstance(instance, nullptr);
    throw;
  }
  vkDestroyInstance(instance, nullptr);
  return result;
}

VKAPI_ATTR VkBool32 VKAPI_CALL VulkanContext::on_validation_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                                     VkDebugUtilsMessageTypeFlagsEXT,
                                                                     const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                                     void* user) {
  auto* self = static_cast<VulkanContext*>(user);
  self->validation_messages_.fetch_add(1);
  std::cerr << "[vulkan validation " << (severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? "error" : "warning")
            << "] " << data->pMessage << "\n";
  return VK_FALSE;
}

VulkanContext::VulkanContext(const Options& options) {
  instance_ = create_instance(options.validation);
  try {
    if (options.validation) {
      VkDebugUtilsMessengerCreateInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
      info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
      info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                         VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
      info.pfnUserCallback = &VulkanContext::on_validation_message;
      info.pUserData = this;
      auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
          vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
      if (!create) throw Error("Vulkan: VK_EXT_debug_utils is not available for validation messages");
      vk_check(create(instance_, &info, nullptr, &messenger_), "vkCreateDebugUtilsMessengerEXT");
    }

    const auto devices = physical_devices(instance_);
    if (devices.empty())
      throw Error("no Vulkan device found; install Mesa's lavapipe (Debian: apt-get install mesa-vulkan-drivers)");
    std::vector<VulkanDeviceInfo> infos;
    for (uint32_t i = 0; i < devices.size(); ++i) infos.push_back(describe(devices[i], i));
    const int picked = pick_device(infos, options.device);
    if (picked < 0) {
      std::string list;
      for (const auto& d : infos) list += "\n  " + std::to_string(d.index) + ": " + d.name + " (" + d.type + ", " + d.driver + ")";
      throw Error("no Vulkan device matches --device '" + options.device + "'; available:" + list +
                  "\n(use lavapipe, gpu, an index, or part of a name)");
    }
    physical_ = devices[picked];
    info_ = infos[picked];
    vkGetPhysicalDeviceProperties(physical_, &properties_);
    vkGetPhysicalDeviceMemoryProperties(physical_, &memory_);

    uint32_t family_count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical_, &family_count, nullptr);
    std::vector<VkQueueFamilyProperties> families(family_count);
    vkGetPhysicalDeviceQueueFamilyProperties(physical_, &family_count, families.data());
    bool found = false;
    for (uint32_t i = 0; i < family_count && !found; ++i) {
      if (families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) {
        queue_family_ = i;
        timestamp_valid_bits_ = families[i].timestampValidBits;
        found = true;
      }
    }
    if (!found) throw Error("Vulkan device '" + info_.name + "' has no compute queue");

    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queue_info.queueFamilyIndex = queue_family_;
    queue_info.queueCount = 1;
    queue_info.pQueuePriorities = &priority;
    VkDeviceCreateInfo device_info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    device_info.queueCreateInfoCount = 1;
    device_info.pQueueCreateInfos = &queue_info;
    VkPhysicalDeviceBufferDeviceAddressFeatures address{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_BUFFER_DEVICE_ADDRESS_FEATURES};
    VkPhysicalDeviceAccelerationStructureFeaturesKHR structures{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR};
    VkPhysicalDeviceRayTracingPipelineFeaturesKHR pipeline{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_PIPELINE_FEATURES_KHR};
    if (options.ray_tracing) {
      const std::string gap = ray_tracing_gap(query_ray_tracing_support(physical_));
      if (!gap.empty()) throw Error("device '" + info_.name + "' " + gap);
      address.bufferDeviceAddress = VK_TRUE;
      structures.accelerationStructure = VK_TRUE;
      pipeline.rayTracingPipeline = VK_TRUE;
      address.pNext = &structures;
      structures.pNext = &pipeline;
      device_info.pNext = &address;
      device_info.enabledExtensionCount = static_cast<uint32_t>(ray_tracing_extensions().size());
      device_info.ppEnabledExtensionNames = ray_tracing_extensions().data();
    }
    vk_check(vkCreateDevice(physical_, &device_info, nullptr, &device_), "vkCreateDevice");
    vkGetDeviceQueue(device_, queue_family_, 0, &queue_);

    VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool_info.queueFamilyIndex = queue_family_;
    vk_check(vkCreateCommandPool(device_, &pool_info, nullptr, &command_pool_), "vkCreateCommandPool");
  } catch (...) {
    release();
    throw;
  }
}

VulkanContext::~VulkanContext() { release(); }

void VulkanContext::release() {
  if (device_) {
    vkDeviceWaitIdle(device_);
    if (command_pool_) vkDestroyCommandPool(device_, command_pool_, nullptr);
    vkDestroyDevice(device_, nullptr);
    device_ = VK_NULL_HANDLE;
  }
  if (messenger_) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy) destroy(instance_, messenger_, nullptr);
    messenger_ = VK_NULL_HANDLE;
  }
  if (instance_) vkDestroyInstance(instance_, nullptr);
  instance_ = VK_NULL_HANDLE;
}

uint32_t VulkanContext::find_memory_type(uint32_t type_bits, VkMemoryPropertyFlags required,
                                         VkMemoryPropertyFlags preferred) const {
  int fallback = -1;
  for (uint32_t i = 0; i < memory_.memoryTypeCount; ++i) {
    if (!(type_bits & (1u << i))) continue;
    const VkMemoryPropertyFlags flags = memory_.memoryTypes[i].propertyFlags;
    if ((flags & required) != required) continue;
    if ((flags & preferred) == preferred) return i;
    if (fallback < 0) fallback = static_cast<int>(i);
  }
  if (fallback < 0) throw Error("Vulkan device '" + info_.name + "' has no memory type with the properties a buffer needs");
  return static_cast<uint32_t>(fallback);
}

}  // namespace sdfbench
