#include "renderers/sdf_vk/sdf_gpu_tables.h"

#include <cstdint>

#include "util/error.h"

namespace sdfbench {
namespace {

constexpr const char* kStructureHint = "a coarser structure needs less (--hash-cell, --octree-depth, --octree-min-objects, --mesh-cell)";

}  // namespace

template <class T>
GpuBuffer upload_table(const VulkanContext& context, const std::vector<T>& data, VkFormat format, size_t texel_bytes,
                       bool storage, const char* what, const char* hint) {
  try {
    GpuBuffer buffer(context, data.size() * sizeof(T),
                     storage ? VK_BUFFER_USAGE_STORAGE_BUFFER_BIT : VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT,
                     GpuBuffer::Use::Upload, what);
    if (!data.empty()) buffer.write(data.data(), data.size() * sizeof(T));
    if (!storage) buffer.texel_view(format, texel_bytes);
    return buffer;
  } catch (const Error& e) {
    throw Error(std::string(e.what()) + "; " + hint);
  }
}

template GpuBuffer upload_table(const VulkanContext&, const std::vector<uint8_t>&, VkFormat, size_t, bool, const char*, const char*);
template GpuBuffer upload_table(const VulkanContext&, const std::vector<uint32_t>&, VkFormat, size_t, bool, const char*, const char*);
template GpuBuffer upload_table(const VulkanContext&, const std::vector<float>&, VkFormat, size_t, bool, const char*, const char*);
template GpuBuffer upload_table(const VulkanContext&, const std::vector<glm::uvec2>&, VkFormat, size_t, bool, const char*, const char*);
template GpuBuffer upload_table(const VulkanContext&, const std::vector<glm::uvec4>&, VkFormat, size_t, bool, const char*, const char*);
template GpuBuffer upload_table(const VulkanContext&, const std::vector<glm::vec4>&, VkFormat, size_t, bool, const char*, const char*);

SdfGpuTables::SdfGpuTables(const VulkanContext& context, const SdfGpuArrays& arrays, bool storage) : storage_(storage) {
  params_ = GpuBuffer(context, sizeof(arrays.params), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, GpuBuffer::Use::Upload,
                      "SDF parameters");
  params_.write(&arrays.params, sizeof(arrays.params));
  auto table = [&](const auto& data, VkFormat format, const char* what) {
    return upload_table(context, data, format, sizeof(data[0]), storage, what, kStructureHint);
  };
  hash_cells_ = table(arrays.hash_cells, VK_FORMAT_R32_UINT, "scene hash cells");
  octree_nodes_ = table(arrays.octree_nodes, VK_FORMAT_R32_UINT, "octree nodes");
  instance_lists_ = table(arrays.instance_lists, VK_FORMAT_R32_UINT, "instance lists");
  instance_records_ = table(arrays.instance_records, VK_FORMAT_R32G32B32A32_UINT, "instance records");
  mesh_records_ = table(arrays.mesh_records, VK_FORMAT_R32G32B32A32_UINT, "mesh records");
  grid_cells_ = table(arrays.grid_cells, VK_FORMAT_R32G32_UINT, "mesh grid cells");
  grid_entries_ = table(arrays.grid_entries, VK_FORMAT_R32G32B32A32_SFLOAT, "mesh grid triangle lists");
  vertices_ = table(arrays.vertices, VK_FORMAT_R32G32B32A32_SFLOAT, "triangle vertices");
  normals_ = table(arrays.normals, VK_FORMAT_R32G32B32A32_SFLOAT, "triangle normals");
  crossing_cells_ = table(arrays.crossing_cells, VK_FORMAT_R32G32_UINT, "exact-hit cells");
  crossing_triangles_ = table(arrays.crossing_triangles, VK_FORMAT_R32_UINT, "exact-hit triangle lists");
}

std::vector<KernelBinding> SdfGpuTables::bindings() const {
  const VkDescriptorType table = storage_ ? VK_DESCRIPTOR_TYPE_STORAGE_BUFFER : VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
  return {{8, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, &params_},
          {9, table, &hash_cells_},
          {10, table, &octree_nodes_},
          {11, table, &instance_lists_},
          {12, table, &instance_records_},
          {13, table, &mesh_records_},
          {14, table, &grid_cells_},
          {15, table, &grid_entries_},
          {16, table, &vertices_},
          {17, table, &normals_},
          {23, table, &crossing_cells_},
          {24, table, &crossing_triangles_}};
}

}  // namespace sdfbench
