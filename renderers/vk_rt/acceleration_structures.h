#pragma once
// The driver's BVH for vk-rt: one bottom-level acceleration structure per mesh (its opaque
// triangles, read from the vertex buffer every triangle backend shares), compacted, and one
// top-level structure with an instance per scene instance (object-to-world transform,
// instanceCustomIndex = instance id). Built on the device with prefer-fast-trace.
#include <cstdint>
#include <vector>

#include "renderers/vk_rt/rt_functions.h"
#include "renderers/vulkan/gpu_buffer.h"
#include "renderers/vulkan/triangle_buffers.h"
#include "scenes/scene.h"

namespace sdfbench {

class AccelerationStructures {
 public:
  // Throws Error when the scene exceeds the device's limits (instances, triangles per mesh).
  AccelerationStructures(const VulkanContext& context, const RayTracingFunctions& functions, const Scene& scene,
                         const TriangleBuffers& tables);
  ~AccelerationStructures();
  AccelerationStructures(const AccelerationStructures&) = delete;
  AccelerationStructures& operator=(const AccelerationStructures&) = delete;

  VkAccelerationStructureKHR top_level() const { return top_level_.handle; }
  // What the structures occupy on the device: the compacted bottom levels plus the top level.
  uint64_t bytes() const;

 private:
  struct Structure {
    GpuBuffer storage;
    VkAccelerationStructureKHR handle = VK_NULL_HANDLE;
  };
  Structure create(VkAccelerationStructureTypeKHR type, VkDeviceSize bytes, const char* what) const;
  void destroy(Structure& s) const;
  void build_bottom_levels(const Scene& scene, const TriangleBuffers& tables);
  void build_top_level(const Scene& scene);

  const VulkanContext& context_;
  const RayTracingFunctions& rt_;
  VkDeviceSize scratch_alignment_ = 1;
  std::vector<Structure> bottom_levels_;  // compacted
  std::vector<int> mesh_level_;           // per mesh: its index in bottom_levels_, -1 without triangles
  Structure top_level_;
  GpuBuffer instances_;
};

}  // namespace sdfbench
