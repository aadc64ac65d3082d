#include "renderers/sdf_bricks/sdf_bricks_renderer.h"

#include <algorithm>
#include <iostream>

#include "renderers/backend.h"
#include "renderers/sdf/sdf_cache.h"
#include "renderers/sdf/sdf_params.h"
#include "renderers/sdf_bricks/brick_gpu_arrays.h"
#include "renderers/sdf_vk/sdf_gpu_arrays.h"
#include "util/error.h"

namespace sdfbench {
namespace {

// No point-triangle distances: trilinear field samples instead.
constexpr uint32_t kBrickCounters = counter_bit(COUNTER_STEPS) | counter_bit(COUNTER_INSTANCE_EVALS) |
                                    counter_bit(COUNTER_FIELD_SAMPLES) | counter_bit(COUNTER_AABB_TESTS) |
                                    counter_bit(COUNTER_TRIANGLE_TESTS) | counter_bit(COUNTER_OUT_OF_STEPS);


std::string kernel_defines(const BackendOptions& options, bool sampler) {
  std::string defines = brick_kernel_defines(options, sampler);
  if (options.params.text("brick_trace") == "min") defines += "#define BRICK_TRACE_MIN 1\n";
  return defines + options.kernel_defines;
}

}  // namespace

sdf::BrickFieldParams brick_field_params(const BackendParams& params, uint64_t max_bytes) {
  sdf::BrickFieldParams p;
  p.voxels = static_cast<uint32_t>(params.integer("voxels"));
  p.band = static_cast<uint32_t>(params.integer("brick_band"));
  p.format = sdf_format_param(params);
  p.max_bytes = max_bytes;
  return p;  // each value in its declaration's range (resolve_params)
}

SdfBricksRenderer::SdfBricksRenderer(const BackendOptions& options)
    : VulkanRenderer(options),
      options_(options),
      field_params_(brick_field_params(options.params, sdf::max_structure_bytes(options.params))),
      hash_params_(sdf::scene_hash_params(options.params)),
      tracing_(sdf::trace_params(options.params)),
      sampler_(use_sampler(options.params.text("brick_fetch"), context_.info())),
      runner_(context_, compute_tile_kernels(context_, "sdf_bricks.comp", kernel_defines(options, sampler_)), kBrickCounters,
              options.whitted_passes) {}

void SdfBricksRenderer::prepare(const Scene& scene) {
  SdfGpuArrays arrays;
  BrickGpuArrays bricks;
  {  // the CPU structures are freed once flattened
    const sdf::SceneSdf sdf =
        sdf::obtain_scene_sdf(scene, sdf::mesh_grid_params(options_.params), hash_params_, options_.cache, std::cerr,
                              {sdf::structure_request(field_params_)});
    const std::vector<sdf::BrickField>& fields = sdf.get<sdf::BrickFields>().fields;
    stats_ = StructureStats{sdf::build_ms(sdf), sdf::bytes(sdf), {}, std::string("brick_fetch=") + (sampler_ ? "sampler" : "texel")};
    arrays = flatten_for_gpu(scene, sdf, tracing_, LeafLists::overlapping_first);
    for (const Instance& instance : scene.instances)
      stats_->instance_voxels.push_back(fields[instance.mesh].voxel * instance.transform.scale);
    const float largest_voxel =
        stats_->instance_voxels.empty() ? 0.0f : *std::max_element(stats_->instance_voxels.begin(), stats_->instance_voxels.end());
    arrays.params.options.y = tracing_.hit == sdf::HitMode::field ? kFieldHitOffsetVoxels * largest_voxel : 0.0f;
    bricks = flatten_brick_fields(fields);
  }
  brick_tables_ = BrickFieldTables(context_, bricks, sampler_, arrays.params, "fewer --voxels or a narrower --brick-band need less");
  tables_ = SdfGpuTables(context_, arrays, tracing_.storage_tables);  // after the atlas layout is in the params
  std::vector<KernelBinding> bindings = tables_.bindings();
  brick_tables_.add_bindings(bindings);
  runner_.set_scene(scene, bindings);
}

BackendInfo sdf_bricks_backend() {
  BackendInfo info;
  info.name = "sdf-bricks";
  info.kind = BackendKind::SdfSampled;
  info.summary = "per-mesh sampled brick fields (UE5's mesh distance fields) on the thesis' hash and octree lists";
  // The thesis' structure for the lists, the mesh grids for exact hits; no cell bounds (its own
  // walk skips empty leaves) and no over-relaxation (it steps by a bound of its field).
  info.params = sdf::sdf_params({"hash_cell", "octree_depth", "octree_min_objects", "octree_min_size", "lists", "mesh_cell",
                                 "cells_per_extent", "fixed_grid", "hit", "max_steps", "storage_tables"},
                                {"exact", "field"});
  info.params.push_back({"voxels", ParamKind::Integer, "128", "brick field lattice cells along each mesh's largest extent",
                         "sampled fields (sdf-bricks, sdf-global)", {}, 4, sdf::kMaxVoxels});
  for (const ParamSpec& spec : brick_field_param_specs()) info.params.push_back(spec);
  info.params.push_back({"brick_trace", ParamKind::Choice, "instance",
                         "instance: each listed instance traced through its own field, t clamped to the best hit (UE5); "
                         "min: the thesis' per-step minimum over the leaf's instances",
                         "sampled fields (sdf-bricks, sdf-global)", {"instance", "min"}});
  info.params.push_back(sdf::sdf_params({"max_structure_mb"}, {"exact"}).front());
  info.counters = info.steps = info.stores_structure = info.scene_hash = true;
  info.partners = {{"sdf-octree", "a sampled per-mesh field against the exact one"},
                   {"bvh", "a sampled per-mesh field against a BVH in a compute kernel"}};
  info.create = factory<SdfBricksRenderer>();
  return info;
}

}  // namespace sdfbench
