#include "renderers/sdf_vk/sdf_vk_renderer.h"

#include <iostream>

#include "renderers/sdf_vk/sdf_gpu_arrays.h"
#include "scenes/error.h"

namespace sdfbench {
namespace {

// One read-only table in a texel buffer. GpuBuffer checks maxTexelBufferElements; the hint
// says which structure parameters shrink the table.
template <class T>
GpuBuffer texel_table(const VulkanContext& context, const std::vector<T>& data, VkFormat format, const char* what) {
  try {
    GpuBuffer buffer(context, data.size() * sizeof(T), VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT, GpuBuffer::Use::Upload,
                     what);
    if (!data.empty()) buffer.write(data.data(), data.size() * sizeof(T));
    buffer.texel_view(format, sizeof(T));
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
                                        (options.tracing.cell_bound ? "#define SDF_CELL_BOUND 1\n" : "") +
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
  hash_cells_ = texel_table(context_, arrays.hash_cells, VK_FORMAT_R32_UINT, "scene hash cells");
  octree_nodes_ = texel_table(context_, arrays.octree_nodes, VK_FORMAT_R32_UINT, "octree nodes");
  instance_lists_ = texel_table(context_, arrays.instance_lists, VK_FORMAT_R32_UINT, "instance lists");
  instance_records_ = texel_table(context_, arrays.instance_records, VK_FORMAT_R32G32B32A32_UINT, "instance records");
  mesh_records_ = texel_table(context_, arrays.mesh_records, VK_FORMAT_R32G32B32A32_UINT, "mesh records");
  grid_cells_ = texel_table(context_, arrays.grid_cells, VK_FORMAT_R32G32_UINT, "mesh grid cells");
  grid_entries_ = texel_table(context_, arrays.grid_entries, VK_FORMAT_R32G32B32A32_SFLOAT, "mesh grid triangle lists");
  vertices_ = texel_table(context_, arrays.vertices, VK_FORMAT_R32G32B32A32_SFLOAT, "triangle vertices");
  normals_ = texel_table(context_, arrays.normals, VK_FORMAT_R32G32B32A32_SFLOAT, "triangle normals");
  const VkDescriptorType texel = VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
  runner_.set_scene(scene, {{8, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, &params_},
                            {9, texel, &hash_cells_},
                            {10, texel, &octree_nodes_},
                            {11, texel, &instance_lists_},
                            {12, texel, &instance_records_},
                            {13, texel, &mesh_records_},
                            {14, texel, &grid_cells_},
                            {15, texel, &grid_entries_},
                            {16, texel, &vertices_},
                            {17, texel, &normals_}});
}

}  // namespace sdfbench
