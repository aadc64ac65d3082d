#include "renderers/sdf_global/sdf_global_renderer.h"

#include <cmath>
#include <iostream>
#include <limits>
#include <sstream>
#include <utility>

#include "renderers/backend.h"
#include "renderers/sdf_global/cell_triangle_refs.h"
#include "renderers/sdf/sdf_cache.h"
#include "renderers/sdf/sdf_params.h"
#include "renderers/sdf_bricks/brick_gpu_arrays.h"
#include "renderers/sdf_vk/sdf_gpu_arrays.h"
#include "util/error.h"

namespace sdfbench {
namespace {

// sdf-bricks' counters (field samples, no point-triangle distances) and the reference cells whose
// triangle set was tested (--exact-lists triangles).
constexpr uint32_t kGlobalCounters = counter_bit(COUNTER_STEPS) | counter_bit(COUNTER_INSTANCE_EVALS) |
                                     counter_bit(COUNTER_FIELD_SAMPLES) | counter_bit(COUNTER_AABB_TESTS) |
                                     counter_bit(COUNTER_TRIANGLE_TESTS) | counter_bit(COUNTER_OUT_OF_STEPS) |
                                     counter_bit(COUNTER_CELL_SETS);


// A table as sdf_global.comp reads it: per stored brick a word that is where its part starts in the
// same buffer (`heads`, offsets into `body`, moved past the heads; kNoCellTable stays), then the
// body. The instance lists: heads s and s + 1 bound stored brick s's instances; --exact-lists
// triangles' cells (global_cell_refs.glsl): head s is brick s's cell table, or none.
std::vector<uint32_t> headed_table(const std::vector<uint32_t>& heads, const std::vector<uint32_t>& body, const char* too_long) {
  const uint64_t offset = heads.size();
  if (offset + body.size() >= std::numeric_limits<uint32_t>::max()) throw Error(too_long);
  std::vector<uint32_t> words;
  words.reserve(offset + body.size());
  for (uint32_t head : heads) words.push_back(head == sdf::kNoCellTable ? head : static_cast<uint32_t>(offset + head));
  words.insert(words.end(), body.begin(), body.end());
  return words;
}

std::string kernel_defines(const BackendOptions& options, bool sampler) {
  std::ostringstream defines;
  defines << brick_kernel_defines(options, sampler);
  // Where the march hands over to the exact test, and how far along the ray one test reaches.
  defines << "#define BRICK_NEAR_VOXELS float(" << options.params.real("exact_near") << ")\n#define BRICK_WINDOW_VOXELS float("
          << options.params.real("exact_window") << ")\n";
  if (options.params.text("hit") == "exact" && options.params.text("exact_lists") == "triangles")
    defines << "#define GLOBAL_REF_SPLIT " << options.params.integer("list_split") << "\n";
  else if (options.params.text("hit") == "exact" && options.params.text("exact_span") == "ray")
    defines << "#define GLOBAL_SPAN_RAY 1\n";
  return defines.str() + options.kernel_defines;
}

}  // namespace

sdf::GlobalFieldParams global_field_params(const BackendParams& params, uint64_t max_bytes) {
  sdf::GlobalFieldParams p;
  p.voxel = params.is_word("global_voxel") ? 0.0f : static_cast<float>(params.real("global_voxel"));  // auto: 0
  p.band = static_cast<uint32_t>(params.integer("brick_band"));
  p.format = sdf_format_param(params);
  p.max_bytes = max_bytes;
  return p;  // each value in its declaration's range (resolve_params)
}

SdfGlobalRenderer::SdfGlobalRenderer(const BackendOptions& options)
    : VulkanRenderer(options),
      options_(options),
      field_params_(global_field_params(options.params, sdf::max_structure_bytes(options.params))),
      tracing_(sdf::trace_params(options.params)),
      sampler_(use_sampler(options.params.text("brick_fetch"), context_.info())),
      runner_(context_,
              compute_tile_kernels(context_, "sdf_global.comp", kernel_defines(options, sampler_)),
              kGlobalCounters, options.whitted_passes) {}

void SdfGlobalRenderer::prepare(const Scene& scene) {
  SdfGpuArrays arrays;
  BrickGpuArrays field;
  std::vector<uint32_t> lists, ref_cells, ref_sets;
  const bool triangle_refs =
      tracing_.hit == sdf::HitMode::exact && options_.params.text("exact_lists") == "triangles";
  {  // the CPU structures are freed once flattened
    const sdf::SceneSdf sdf =
        sdf::obtain_scene_sdf(scene, sdf::mesh_grid_params(options_.params), sdf::one_cell_hash(scene, field_params_.max_bytes),
                              options_.cache, std::cerr, {sdf::structure_request(field_params_)});
    const sdf::GlobalField& global_field = sdf.get<sdf::GlobalFieldStructure>().field;
    // What the kernel reads: the mesh grids (exact hits) and the global field with its lists.
    double ms = global_field.build_ms;
    size_t bytes = global_field.bytes();
    for (const sdf::MeshDistanceGrid& grid : sdf.mesh_grids) ms += grid.build_ms, bytes += grid.bytes();
    // The resolved fetch path and voxel (--global-voxel auto is the scene's) go into the row.
    std::ostringstream resolved;
    resolved << "brick_fetch=" << (sampler_ ? "sampler" : "texel") << " voxel=" << global_field.field.voxel;
    if (triangle_refs) {  // built with the field each time (not cached): their time is in the row
      sdf::CellTriangleRefs refs = sdf::build_cell_triangle_refs(
          scene, global_field.field, static_cast<uint32_t>(options_.params.integer("list_split")), field_params_.max_bytes);
      ms += refs.build_ms;
      bytes += refs.bytes();
      resolved << " references=" << refs.references << " set_words=" << refs.sets.size()
               << " reference_mb=" << std::round(refs.bytes() / 1e5) / 10;
      ref_cells = headed_table(refs.brick_tables, refs.cells,
                               "the triangle references' cell tables are too long for the kernel's 32-bit indices; use a "
                               "smaller --list-split");
      ref_sets = std::move(refs.sets);
    }
    stats_ = StructureStats{ms, bytes, {}, resolved.str()};
    stats_->instance_voxels.assign(scene.instances.size(), global_field.field.voxel);
    arrays = flatten_for_gpu(scene, sdf, tracing_);
    arrays.hash_cells = {0u};
    arrays.octree_nodes = {0u};
    arrays.instance_lists = {0u, 0u};
    arrays.params.options.y = tracing_.hit == sdf::HitMode::field ? kFieldHitOffsetVoxels * global_field.field.voxel : 0.0f;
    field = flatten_brick_fields({global_field.field});
    lists = headed_table(global_field.list_begin, global_field.list_instances,
                         "the global field's instance lists are too long for the kernel's 32-bit indices; use a larger "
                         "--global-voxel");
  }
  const char* hint = "a larger --global-voxel, a narrower --brick-band or --sdf-format f16/u8 need less";
  field_tables_ = BrickFieldTables(context_, field, sampler_, arrays.params, hint);
  brick_lists_ = upload_table(context_, lists, VK_FORMAT_R32_UINT, 4, false, "global field instance lists", hint);
  tables_ = SdfGpuTables(context_, arrays, tracing_.storage_tables);  // after the atlas layout is in the params
  std::vector<KernelBinding> bindings = tables_.bindings();
  field_tables_.add_bindings(bindings);
  bindings.push_back({22, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, &brick_lists_});
  if (triangle_refs) {
    const char* refs_hint = "a smaller --list-split, a larger --global-voxel or --exact-lists instances need less";
    ref_cells_ = upload_table(context_, ref_cells, VK_FORMAT_R32_UINT, 4, false, "triangle reference cells", refs_hint);
    ref_sets_ = upload_table(context_, ref_sets, VK_FORMAT_R32_UINT, 4, false, "triangle reference sets", refs_hint);
    bindings.push_back({25, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, &ref_cells_});
    bindings.push_back({26, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, &ref_sets_});
  }
  runner_.set_scene(scene, bindings);
}

BackendInfo sdf_global_backend() {
  BackendInfo info;
  info.name = "sdf-global";
  info.kind = BackendKind::SdfSampled;
  info.summary = "one sampled field over the whole scene (UE5's global distance field), exact hits on the mesh grids";
  // No scene hash, cell bounds or over-relaxation: one field bounds all of space.
  info.params = sdf::sdf_params({"mesh_cell", "cells_per_extent", "fixed_grid", "hit", "max_steps", "storage_tables"},
                                {"exact", "field"});
  info.params.push_back({"global_voxel", ParamKind::Real, "auto",
                         "the global field's voxel in world units; auto: the median instance's largest extent / 10 "
                         "(docs/backends.md, \"sdf-global\")",
                         "sampled fields (sdf-bricks, sdf-global)", {"auto"}, 1e-6, 1e9});
  info.params.push_back({"exact_lists", ParamKind::Choice, "instances",
                         "--hit exact's candidates near a surface: instances (the brick's instances, each through its mesh "
                         "grid) or triangles (per-cell (instance, triangle) references built with the field, each cell's "
                         "set tested once; docs/backends.md, \"sdf-global\")",
                         "sampled fields (sdf-bricks, sdf-global)", {"instances", "triangles"}, 0, 0, false, "hit", "exact"});
  info.params.push_back({"list_split", ParamKind::Integer, "1",
                         "--exact-lists triangles: reference cells per voxel and axis (finer cells, fewer triangles per set, "
                         "more cells)",
                         "sampled fields (sdf-bricks, sdf-global)", {}, 1, sdf::kMaxListSplit, false, "exact_lists", "triangles"});
  info.params.push_back({"exact_span", ParamKind::Choice, "window",
                         "--exact-lists instances: what one exact test of a listed instance covers: window (the next "
                         "--exact-window voxels) or ray (the rest of the ray, once per instance; a brick whose instances "
                         "are all tested is passed whole, so the march never creeps onto a tested surface)",
                         "sampled fields (sdf-bricks, sdf-global)", {"window", "ray"}, 0, 0, false, "exact_lists", "instances"});
  info.params.push_back({"exact_near", ParamKind::Real, "0.5",
                         "--hit exact: the march hands over to the exact test where the field's bound falls below this "
                         "many voxels (smaller: more steps, fewer tests)",
                         "sampled fields (sdf-bricks, sdf-global)", {}, 0.01, 8, false, "hit", "exact"});
  info.params.push_back({"exact_window", ParamKind::Real, "8",
                         "--hit exact: one exact test covers this many voxels of the ray (within the brick; larger: fewer "
                         "tests, each longer)",
                         "sampled fields (sdf-bricks, sdf-global)", {}, 0.5, 64, false, "hit", "exact"});
  for (const ParamSpec& spec : brick_field_param_specs()) info.params.push_back(spec);
  info.params.push_back(sdf::sdf_params({"max_structure_mb"}, {"exact"}).front());
  info.counters = info.steps = info.stores_structure = true;
  info.partners = {{"sdf-octree", "one sampled scene-wide field against the thesis' structure"},
                   {"bvh", "one sampled scene-wide field against a BVH in a compute kernel"}};
  info.create = factory<SdfGlobalRenderer>();
  return info;
}

}  // namespace sdfbench
