#pragma once
// The SDF structure's tables (SdfGpuArrays) uploaded for a kernel: texel buffers, or storage
// buffers with --storage-tables, bound at 8-17 as sdf_scene_distance.glsl declares them (23-24:
// the exact hits' lists, sdf_exact_crossing.glsl). Shared by sdf-hash/sdf-octree, sdf-bricks and
// sdf-global, whose kernels read the same mesh grids and records.
#include <vector>

#include "renderers/sdf_vk/sdf_gpu_arrays.h"
#include "renderers/vulkan/descriptor_set.h"
#include "renderers/vulkan/gpu_buffer.h"
#include "renderers/vulkan/vulkan_context.h"

namespace sdfbench {

// One read-only table in a texel buffer of `format`, or (storage) a storage buffer. GpuBuffer
// checks the device's limits; `hint` says what shrinks the table.
template <class T>
GpuBuffer upload_table(const VulkanContext& context, const std::vector<T>& data, VkFormat format, size_t texel_bytes,
                       bool storage, const char* what, const char* hint);

class SdfGpuTables {
 public:
  SdfGpuTables() = default;
  SdfGpuTables(const VulkanContext& context, const SdfGpuArrays& arrays, bool storage);
  std::vector<KernelBinding> bindings() const;

 private:
  bool storage_ = false;
  GpuBuffer params_, hash_cells_, octree_nodes_, instance_lists_, instance_records_, mesh_records_, grid_cells_,
      grid_entries_, vertices_, normals_, crossing_cells_, crossing_triangles_;
};

}  // namespace sdfbench
