#include "renderers/sdf_vk/sdf_vk_renderer.h"

#include <iostream>

#include "renderers/backend_registry.h"
#include "renderers/sdf/sdf_params.h"
#include "renderers/sdf_vk/sdf_gpu_arrays.h"
#include "util/error.h"

namespace sdfbench {

SdfVkRenderer::SdfVkRenderer(std::string name, const BackendOptions& options)
    : VulkanRenderer(options),
      name_(std::move(name)),
      options_(options),
      tracing_(sdf::trace_params(options.params)),
      hash_params_(sdf::scene_hash_params(options.params)),
      runner_(context_, compute_tile_kernels(context_, "sdf_trace.comp",
                                        std::string(tracing_.cell_bound ? "#define SDF_CELL_BOUND 1\n" : "") +
                                            (tracing_.storage_tables ? "#define SDF_STORAGE_TABLES 1\n" : "") +
                                            options.kernel_defines), kSdfCounters, options.whitted_passes) {}

void SdfVkRenderer::prepare(const Scene& scene) {
  const SdfGpuArrays arrays = [&] {  // the CPU structures are freed once flattened
    const sdf::SceneSdf sdf =
        sdf::obtain_scene_sdf(scene, sdf::mesh_grid_params(options_.params), hash_params_, options_.cache, std::cerr);
    stats_ = StructureStats{sdf::build_ms(sdf), sdf::bytes(sdf)};
    return flatten_for_gpu(scene, sdf, tracing_);
  }();
  tables_ = SdfGpuTables(context_, arrays, tracing_.storage_tables);
  runner_.set_scene(scene, tables_.bindings());
}

namespace {

// The thesis' exact structure, sphere-traced in sdf_trace.comp: what sdf-hash and sdf-octree own.
const std::vector<std::string> kExactKernelParams = {
    "hash_cell", "lists",  "mesh_cell",  "cells_per_extent", "fixed_grid",     "hit",           "max_steps",
    "hit_epsilon", "hit_footprint", "over_relax", "cell_bound", "storage_tables", "max_structure_mb"};
const std::vector<std::string> kOctreeParams = {"octree_depth", "octree_min_objects", "octree_min_size"};

BackendInfo exact_kernel_backend(const std::string& name, std::vector<ParamSpec> params) {
  BackendInfo info;
  info.name = name;
  info.kind = "sdf-exact";
  info.params = std::move(params);
  info.counters = info.steps = info.stores_structure = true;
  info.create = [name](const BackendOptions& options) { return std::make_unique<SdfVkRenderer>(name, options); };
  return info;
}

}  // namespace

BackendInfo sdf_hash_backend() {
  // The thesis' table 6.2: a hash of cell 1, no octree.
  std::vector<ParamSpec> params = sdf::sdf_params(kExactKernelParams, {"exact", "thesis"});
  params.front() = with_default(params.front(), "1");
  BackendInfo info = exact_kernel_backend("sdf-hash", std::move(params));
  info.summary = "the thesis' spatial hash (cell 1, no octree) over exact per-mesh distance grids, sphere-traced";
  return info;
}

BackendInfo sdf_octree_backend() {
  std::vector<std::string> names = kExactKernelParams;
  names.insert(names.begin() + 1, kOctreeParams.begin(), kOctreeParams.end());
  BackendInfo info = exact_kernel_backend("sdf-octree", sdf::sdf_params(names, {"exact", "thesis"}));
  info.summary = "the thesis' spatial hash of octrees (cell 10, min node size 1) over exact per-mesh distance grids";
  info.partners = {{"vk-rt", "the thesis' structure against the driver's BVH"}};
  return info;
}

}  // namespace sdfbench
