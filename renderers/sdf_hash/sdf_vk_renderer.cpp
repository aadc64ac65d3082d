#include <iostream>
#include <string>

#include "renderers/backend.h"
#include "renderers/renderer.h"
#include "renderers/sdf/scene_hash.h"
#include "renderers/sdf/sdf_cache.h"
#include "renderers/sdf/sdf_params.h"
#include "renderers/sdf/sphere_tracer.h"
#include "renderers/sdf_vk/sdf_gpu_arrays.h"
#include "renderers/sdf_vk/sdf_gpu_tables.h"
#include "renderers/vulkan/vulkan_frame_runner.h"
#include "renderers/vulkan/vulkan_renderer.h"
#include "util/error.h"

namespace sdfbench {

// The thesis' renderer, Vulkan compute: sphere tracing through the scene hash (+ octrees) and
// the per-mesh distance grids. One class, one kernel (sdf_trace.comp) for both backends:
// "sdf-hash" builds with octree depth 0 and hash cell 1 (thesis table 6.2), "sdf-octree" with
// the given octree parameters (table 6.1); each declares the parameters it owns.
class SdfVkRenderer : public VulkanRenderer {
 public:
  SdfVkRenderer(std::string name, const BackendOptions& options);
  std::string name() const override { return name_; }
  void prepare(const Scene& scene) override;
  FrameResult render(const FrameRequest& request) override { return runner_.run(request); }
  std::optional<StructureStats> structure_stats() const override { return stats_; }

 private:
  std::string name_;
  BackendOptions options_;
  std::optional<StructureStats> stats_;  // of the CPU structures the GPU tables were flattened from
  sdf::SphereTraceParams tracing_;
  sdf::SceneHashParams hash_params_;  // sdf-hash: octree depth 0 (it owns no octree parameters)
  SdfGpuTables tables_;
  VulkanFrameRunner runner_;  // declared last: destroyed first, before the buffers it binds
};

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
  info.kind = BackendKind::SdfExact;
  info.params = std::move(params);
  info.counters = info.steps = info.stores_structure = info.scene_hash = true;
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
