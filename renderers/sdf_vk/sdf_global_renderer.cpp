#include "renderers/sdf_vk/sdf_global_renderer.h"

#include <iostream>
#include <limits>
#include <sstream>

#include "renderers/sdf/sdf_cache.h"
#include "renderers/sdf_vk/brick_gpu_arrays.h"
#include "renderers/sdf_vk/sdf_gpu_arrays.h"
#include "util/error.h"

namespace sdfbench {
namespace {

// The per-brick instance lists as sdf_global.comp reads them: word s (s <= stored bricks) is where
// stored brick s's instances start in the same buffer, word s + 1 where they end.
std::vector<uint32_t> flatten_lists(const sdf::GlobalField& global) {
  const size_t offset = global.list_begin.size();
  if (offset + global.list_instances.size() >= std::numeric_limits<uint32_t>::max())
    throw Error("the global field's instance lists are too long for the kernel's 32-bit indices; use a larger --global-voxel");
  std::vector<uint32_t> words;
  words.reserve(offset + global.list_instances.size());
  for (uint32_t begin : global.list_begin) words.push_back(static_cast<uint32_t>(offset + begin));
  words.insert(words.end(), global.list_instances.begin(), global.list_instances.end());
  return words;
}

}  // namespace

sdf::GlobalFieldParams global_field_params(const BackendParams& params, uint64_t max_bytes) {
  sdf::GlobalFieldParams p;
  p.voxel = params.get("global_voxel") == "auto" ? 0.0f : static_cast<float>(params.real("global_voxel"));
  p.band = static_cast<uint32_t>(params.integer("brick_band"));
  p.format = sdf_format_param(params);
  p.max_bytes = max_bytes;
  sdf::validate(p);
  return p;
}

SdfGlobalRenderer::SdfGlobalRenderer(const BackendOptions& options)
    : options_(options),
      field_params_(global_field_params(options.params, options.mesh_grid.max_bytes)),
      context_(VulkanContext::Options{options.device, options.validation}),
      sampler_(use_sampler(options.params.get("brick_fetch"), context_.info())),
      runner_(context_,
              compute_tile_kernels(context_, "sdf_global.comp", brick_kernel_defines(options, sampler_) + options.kernel_defines),
              kBrickCounters, options.whitted_passes) {
  sdf::validate(options_.scene_hash);
  sdf::check_exact_field_hit(options_.tracing.hit, name());
  if (options_.tracing.cell_bound) throw Error("--cell-bound: sdf-global has no scene hash cells; its field bounds empty space");
  if (options_.tracing.over_relax != 1.0f) throw Error("--over-relax: sdf-global steps by a bound of its field, not over-relaxed");
}

void SdfGlobalRenderer::prepare(const Scene& scene) {
  SdfGpuArrays arrays;
  BrickGpuArrays field;
  std::vector<uint32_t> lists;
  {  // the CPU structures are freed once flattened
    const sdf::SceneSdf sdf =
        sdf::obtain_scene_sdf(scene, options_.mesh_grid, options_.scene_hash, options_.cache, std::cerr, nullptr, &field_params_);
    // What the kernel reads: the mesh grids (exact hits) and the global field with its lists. (The
    // scene hash, built for the cache the other SDF backends share, is neither uploaded nor counted.)
    double ms = sdf.global_field.build_ms;
    size_t bytes = sdf.global_field.bytes();
    for (const sdf::MeshDistanceGrid& grid : sdf.mesh_grids) ms += grid.build_ms, bytes += grid.bytes();
    // The resolved fetch path and voxel (--global-voxel auto is the scene's) go into the row.
    std::ostringstream resolved;
    resolved << "brick_fetch=" << (sampler_ ? "sampler" : "texel") << " voxel=" << sdf.global_field.field.voxel;
    stats_ = StructureStats{ms, bytes, {}, resolved.str()};
    stats_->instance_voxels.assign(scene.instances.size(), sdf.global_field.field.voxel);
    arrays = flatten_for_gpu(scene, sdf, options_.tracing);
    arrays.hash_cells = {0u};
    arrays.octree_nodes = {0u};
    arrays.instance_lists = {0u, 0u};
    arrays.params.options.y = options_.tracing.hit == sdf::HitMode::field ? kFieldHitOffsetVoxels * sdf.global_field.field.voxel : 0.0f;
    field = flatten_brick_fields({sdf.global_field.field});
    lists = flatten_lists(sdf.global_field);
  }
  const char* hint = "a larger --global-voxel, a narrower --brick-band or --sdf-format f16/u8 need less";
  field_tables_ = BrickFieldTables(context_, field, sampler_, arrays.params, hint);
  brick_lists_ = upload_table(context_, lists, VK_FORMAT_R32_UINT, 4, false, "global field instance lists", hint);
  tables_ = SdfGpuTables(context_, arrays, options_.tracing.storage_tables);  // after the atlas layout is in the params
  std::vector<KernelBinding> bindings = tables_.bindings();
  field_tables_.add_bindings(bindings);
  bindings.push_back({22, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, &brick_lists_});
  runner_.set_scene(scene, bindings);
}

}  // namespace sdfbench
