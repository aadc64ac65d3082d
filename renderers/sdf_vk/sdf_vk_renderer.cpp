#include "renderers/sdf_vk/sdf_vk_renderer.h"

#include <iostream>

#include "renderers/sdf_vk/sdf_gpu_arrays.h"
#include "util/error.h"

namespace sdfbench {
namespace {

// One read-only table in a texel buffer, or with --storage-tables a storage buffer. GpuBuffer
// checks maxTexelBufferElements or maxStorageBufferRange; the hint says which structure
// parameters shrink the table.
template <class T>
GpuBuffer sdf_table(const VulkanContext& context, const std::vector<T>& data, VkFormat format, bool storage, const char* what) {
  try {
    GpuBuffer buffer(context, data.size() * sizeof(T),
                     storage ? VK_BUFFER_USAGE_STORAGE_BUFFER_BIT : VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT,
                     GpuBuffer::Use::Upload, what);
    if (!data.empty()) buffer.write(data.data(), data.size() * sizeof(T));
    if (!storage) buffer.texel_view(format, sizeof(T));
    return buffer;
  } catch (const Error& e) {
    throw Error(std::string(e.what()) +
                "; a coarser structure needs less (--hash-cell, --octree-depth, --octree-min-objects, --mesh-cell)");
  }
}

}  // namespace

SdfVkRenderer::SdfVkRenderer(std::string name, const BackendOptions& options)
    : name_(std::move(name)),
      options_(options),
      context_(VulkanContext::Options{options.device, options.validation}),
      runner_(context_, compute_tile_kernels(context_, "sdf_trace.comp",
                                        std::string(options.tracing.cell_bound ? "#define SDF_CELL_BOUND 1\n" : "") +
                                            (options.tracing.storage_tables ? "#define SDF_STORAGE_TABLES 1\n" : "") +
                                            options.kernel_defines), kSdfCounters, options.whitted_passes) {
  sdf::validate(scene_hash_params_for(name_, options_));
}

void SdfVkRenderer::prepare(const Scene& scene) {
  const SdfGpuArrays arrays = [&] {  // the CPU structures are freed once flattened
    const sdf::SceneSdf sdf = sdf::obtain_scene_sdf(scene, options_.mesh_grid, scene_hash_params_for(name_, options_),
                                                    options_.cache, std::cerr);
    stats_ = StructureStats{sdf::build_ms(sdf), sdf::bytes(sdf)};
    return flatten_for_gpu(scene, sdf, options_.tracing);
  }();
  params_ = GpuBuffer(context_, sizeof(arrays.params), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, GpuBuffer::Use::Upload,
                      "SDF parameters");
  params_.write(&arrays.params, sizeof(arrays.params));
  const bool storage = options_.tracing.storage_tables;
  hash_cells_ = sdf_table(context_, arrays.hash_cells, VK_FORMAT_R32_UINT, storage, "scene hash cells");
  octree_nodes_ = sdf_table(context_, arrays.octree_nodes, VK_FORMAT_R32_UINT, storage, "octree nodes");
  instance_lists_ = sdf_table(context_, arrays.instance_lists, VK_FORMAT_R32_UINT, storage, "instance lists");
  instance_records_ = sdf_table(context_, arrays.instance_records, VK_FORMAT_R32G32B32A32_UINT, storage, "instance records");
  mesh_records_ = sdf_table(context_, arrays.mesh_records, VK_FORMAT_R32G32B32A32_UINT, storage, "mesh records");
  grid_cells_ = sdf_table(context_, arrays.grid_cells, VK_FORMAT_R32G32_UINT, storage, "mesh grid cells");
  grid_entries_ = sdf_table(context_, arrays.grid_entries, VK_FORMAT_R32G32B32A32_SFLOAT, storage, "mesh grid triangle lists");
  vertices_ = sdf_table(context_, arrays.vertices, VK_FORMAT_R32G32B32A32_SFLOAT, storage, "triangle vertices");
  normals_ = sdf_table(context_, arrays.normals, VK_FORMAT_R32G32B32A32_SFLOAT, storage, "triangle normals");
  const VkDescriptorType table = storage ? VK_DESCRIPTOR_TYPE_STORAGE_BUFFER : VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
  runner_.set_scene(scene, {{8, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, &params_},
                            {9, table, &hash_cells_},
                            {10, table, &octree_nodes_},
                            {11, table, &instance_lists_},
                            {12, table, &instance_records_},
                            {13, table, &mesh_records_},
                            {14, table, &grid_cells_},
                            {15, table, &grid_entries_},
                            {16, table, &vertices_},
                            {17, table, &normals_}});
}

}  // namespace sdfbench
