#include "renderers/sdf_vk/sdf_bricks_renderer.h"

#include <algorithm>
#include <iostream>

#include "renderers/sdf_vk/brick_gpu_arrays.h"
#include "renderers/sdf_vk/sdf_gpu_arrays.h"
#include "util/error.h"

namespace sdfbench {
namespace {

std::string kernel_defines(const BackendOptions& options, bool sampler) {
  std::string defines = brick_kernel_defines(options, sampler);
  if (options.params.get("brick_trace") == "min") defines += "#define BRICK_TRACE_MIN 1\n";
  return defines + options.kernel_defines;
}

}  // namespace

sdf::BrickFieldParams brick_field_params(const BackendParams& params, uint64_t max_bytes) {
  sdf::BrickFieldParams p;
  p.voxels = static_cast<uint32_t>(params.integer("voxels"));
  p.band = static_cast<uint32_t>(params.integer("brick_band"));
  p.format = sdf_format_param(params);
  p.max_bytes = max_bytes;
  sdf::validate(p);
  return p;
}

SdfBricksRenderer::SdfBricksRenderer(const BackendOptions& options)
    : options_(options),
      field_params_(brick_field_params(options.params, options.mesh_grid.max_bytes)),
      context_(VulkanContext::Options{options.device, options.validation}),
      sampler_(use_sampler(options.params.get("brick_fetch"), context_.info())),
      runner_(context_, compute_tile_kernels(context_, "sdf_bricks.comp", kernel_defines(options, sampler_)), kBrickCounters,
              options.whitted_passes) {
  sdf::validate(options_.scene_hash);
  sdf::check_exact_field_hit(options_.tracing.hit, name());
  if (options_.tracing.cell_bound) throw Error("--cell-bound: sdf-bricks skips empty leaves by its own walk; it has no cell bounds");
  if (options_.tracing.over_relax != 1.0f) throw Error("--over-relax: sdf-bricks steps by a bound of its field, not over-relaxed");
}

void SdfBricksRenderer::prepare(const Scene& scene) {
  SdfGpuArrays arrays;
  BrickGpuArrays bricks;
  {  // the CPU structures are freed once flattened
    const sdf::SceneSdf sdf =
        sdf::obtain_scene_sdf(scene, options_.mesh_grid, options_.scene_hash, options_.cache, std::cerr, &field_params_);
    const std::vector<sdf::BrickField>& fields = sdf.brick_fields;
    stats_ = StructureStats{sdf::build_ms(sdf), sdf::bytes(sdf), {}, std::string("brick_fetch=") + (sampler_ ? "sampler" : "texel")};
    arrays = flatten_for_gpu(scene, sdf, options_.tracing, LeafLists::overlapping_first);
    for (const Instance& instance : scene.instances)
      stats_->instance_voxels.push_back(fields[instance.mesh].voxel * instance.transform.scale);
    const float largest_voxel =
        stats_->instance_voxels.empty() ? 0.0f : *std::max_element(stats_->instance_voxels.begin(), stats_->instance_voxels.end());
    arrays.params.options.y = options_.tracing.hit == sdf::HitMode::field ? kFieldHitOffsetVoxels * largest_voxel : 0.0f;
    bricks = flatten_brick_fields(fields);
  }
  brick_tables_ = BrickFieldTables(context_, bricks, sampler_, arrays.params, "fewer --voxels or a narrower --brick-band need less");
  tables_ = SdfGpuTables(context_, arrays, options_.tracing.storage_tables);  // after the atlas layout is in the params
  std::vector<KernelBinding> bindings = tables_.bindings();
  brick_tables_.add_bindings(bindings);
  runner_.set_scene(scene, bindings);
}

}  // namespace sdfbench
