// `sdfbench info`: what this machine offers the benchmark.
#include <algorithm>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "harness/commands.h"
#include "harness/system_info.h"
#include "renderers/embree/embree_api.h"
#include "renderers/backend_registry.h"
#include "renderers/vulkan/loop_cap_probe.h"
#include "renderers/vulkan/ray_tracing_support.h"
#include "renderers/vulkan/vulkan_context.h"
#include "scenes/mesh.h"
#include "util/cpu_info.h"
#include "util/error.h"
#include "util/input_file.h"

namespace sdfbench {
namespace {

// Runs the loop-cap probe on the device: drivers with a cap get whitted in passes and flag (✂)
// what the cap cuts short (docs/limits.md, "The loop limit").
std::string describe_loop_cap(const VulkanDeviceInfo& device) {
  try {
    const VulkanContext context(VulkanContext::Options{std::to_string(device.index), false});
    if (!has_loop_cap(context)) return "none (a loop of " + std::to_string(kLoopCapProbeTrips) + " iterations ran in full)";
    return "yes, a loop of " + std::to_string(kLoopCapProbeTrips) +
           " iterations stopped short (lavapipe before Mesa 25: 65535 per invocation); whitted runs in passes, "
           "cut pixels are flagged";
  } catch (const Error& e) {
    return std::string("not probed: ") + e.what();
  }
}

// Whether the device can run vk-rt (the ray-tracing pipeline extensions and features).
std::string describe_ray_tracing(const VulkanDeviceInfo& device) {
  try {
    const VulkanContext context(VulkanContext::Options{std::to_string(device.index), false});
    const std::string gap = ray_tracing_gap(query_ray_tracing_support(context.physical_device()));
    return gap.empty() ? "yes (VK_KHR_ray_tracing_pipeline, VK_KHR_acceleration_structure)" : "no: " + gap;
  } catch (const Error& e) {
    return std::string("not probed: ") + e.what();
  }
}

// What differs between devices and matters to the measurements (issue 17): the subgroup width
// the kernels' lanes run in, the timestamp counter (valid bits, period), the largest tables.
std::string describe_limits(const VulkanDeviceInfo& device) {
  try {
    const VulkanContext context(VulkanContext::Options{std::to_string(device.index), false});
    VkPhysicalDeviceSubgroupProperties subgroup{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
    VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    properties.pNext = &subgroup;
    vkGetPhysicalDeviceProperties2(context.physical_device(), &properties);
    VkPhysicalDeviceMemoryProperties memory;
    vkGetPhysicalDeviceMemoryProperties(context.physical_device(), &memory);
    uint64_t device_local = 0;
    for (uint32_t i = 0; i < memory.memoryHeapCount; ++i)
      if (memory.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT) device_local = std::max(device_local, memory.memoryHeaps[i].size);
    const VkPhysicalDeviceLimits& limits = properties.properties.limits;
    std::ostringstream out;
    out << "subgroup " << subgroup.subgroupSize << ", timestamps " << context.timestamp_valid_bits() << " bits x "
        << limits.timestampPeriod << " ns, texel buffers " << limits.maxTexelBufferElements << " texels, storage buffers "
        << describe_bytes(limits.maxStorageBufferRange) << ", device-local memory " << describe_bytes(device_local);
    return out.str();
  } catch (const Error& e) {
    return std::string("not read: ") + e.what();
  }
}

void print_info() {
  std::cout << "sdfbench " << SDFBENCH_VERSION << " (commit " << git_commit() << ")\n\n";
  std::cout << "CPU:     " << cpu_model() << ", " << hardware_threads() << " hardware threads; CPU backends use "
            << cpu_thread_count(BackendOptions{}) << " threads\n";
  std::cout << "Embree:  " << embree::version() << " (the embree backend and the bvh backend's builder)\n\n";

  std::cout << "Vulkan devices (--device):\n";
  try {
    const auto devices = VulkanContext::list_devices();
    if (devices.empty()) std::cout << "  none found (install mesa-vulkan-drivers for lavapipe)\n";
    bool default_marked = false;
    for (const VulkanDeviceInfo& d : devices) {
      const bool is_default = !default_marked && d.type == "cpu";
      default_marked = default_marked || is_default;
      std::cout << "  " << d.index << ": " << d.name << "\n     type " << d.type << ", driver " << d.driver << " ("
                << d.driver_info << "), Vulkan " << d.api_version << (is_default ? "  [default]" : "") << "\n";
      std::cout << "     loop cap: " << describe_loop_cap(d) << "\n";
      std::cout << "     vk-rt:    " << describe_ray_tracing(d) << "\n";
      std::cout << "     limits:   " << describe_limits(d) << "\n";
    }
  } catch (const Error& e) {
    std::cout << "  unavailable: " << e.what() << "\n";
  }

  std::cout << "\nThesis meshes (" << (data_dir() / "meshes").string() << "):\n";
  for (const std::string& name : thesis_mesh_names()) {
    std::cout << "  " << std::left << std::setw(8) << name;
    try {
      const Mesh mesh = load_obj(builtin_mesh_path(name), name);
      std::cout << std::right << std::setw(6) << mesh.triangle_count() << " triangles " << std::setw(6)
                << mesh.positions.size() << " vertices\n";
    } catch (const Error& e) {
      std::cout << "unavailable: " << e.what() << "\n";
    }
  }

  std::cout << "\nBackends: " << backend_list() << " (`sdfbench backends` describes each and its parameters)\n";
}

}  // namespace

void register_info_command(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("info", "List Vulkan devices, CPU, threads, backends and the thesis meshes");
  cmd->callback(print_info);
}

}  // namespace sdfbench
