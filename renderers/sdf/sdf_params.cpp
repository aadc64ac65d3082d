#include "renderers/sdf/sdf_params.h"

#include "util/error.h"

namespace sdfbench::sdf {
namespace {

ListRule list_rule(const std::string& text) { return text == "thesis" ? ListRule::Thesis : ListRule::Exact; }

HitMode hit_mode(const std::string& text) {
  return text == "thesis" ? HitMode::thesis : text == "field" ? HitMode::field : HitMode::exact;
}

}  // namespace

const std::vector<ParamSpec>& sdf_param_specs() {
  using K = ParamKind;
  const std::string structures = "SDF structures", tracing = "SDF tracing";
  static const std::vector<ParamSpec> specs = {
      {"hash_cell", K::Real, "10", "scene hash cell size in world units (thesis: 10 with octree, 1 without)", structures, {}, 1e-6, 1e9},
      {"octree_depth", K::Integer, "4", "octree depth per hash cell (0: hash only)", structures, {}, 0, 16},
      {"octree_min_objects", K::Integer, "1", "octree leaf when a node lists <= this many instances", structures, {}, 1, 1e6},
      {"octree_min_size", K::Real, "1", "octree leaf when a node's edge is <= this (thesis: 1)", structures, {}, 1e-6, 1e9},
      {"lists", K::Choice, "exact", "instance lists: exact (instances whose surface can be the nearest) or thesis (influence AABB)",
       structures, {"exact", "thesis"}},
      {"mesh_cell", K::Real, "0", "mesh distance grid cell size in mesh units (0: from --cells-per-extent)", structures, {}, 0, 1e9},
      {"cells_per_extent", K::Integer, "32", "mesh grid cells along the mesh's largest extent (with --mesh-cell 0)", structures, {}, 1,
       1024, false, "mesh_cell", "0"},
      {"fixed_grid", K::Flag, "0",
       "keep --cells-per-extent for meshes over 8192 triangles too (default: finer with the triangle count, far cells as "
       "bounds; docs/measured.md, \"Large meshes\")",
       structures, {}, 0, 0, false, "mesh_cell", "0"},
      {"hit", K::Choice, "exact",
       "exact: the ray's crossing with the triangles listed where it converged; thesis: the converged point, the closest "
       "point's normal and uv; field (sampled fields): the field's own crossing and gradient normal, its accuracy in the row",
       tracing, {"exact", "thesis", "field"}},
      {"max_steps", K::Integer, "512", "sphere-tracing steps per ray", tracing, {}, 1, 1e6},
      {"hit_epsilon", K::Real, "5e-06",
       "--hit thesis: sphere-tracing hit distance, relative to the scene size (beyond 1e-2 objects blur and vanish)", tracing, {},
       1e-8, 1e-2},
      {"hit_footprint", K::Real, "0.25", "--hit exact: hit distance as a fraction of a pixel's footprint at the ray's length",
       tracing, {}, 1e-4, 1},
      {"over_relax", K::Real, "1",
       "over-relaxed sphere tracing (Keinert et al. 2014): steps of this x the distance, checked and undone where they may "
       "have jumped a surface; 1: the thesis' plain sphere tracing",
       tracing, {}, 1, 1.95},
      {"cell_bound", K::Flag, "0",
       "a step from an octree leaf (hash cell) that no listed instance's box comes near crosses it without evaluating an "
       "instance (off: the thesis' step everywhere)",
       tracing},
      {"storage_tables", K::Flag, "0",
       "the structure's tables in storage buffers instead of texel buffers (the same data and images; which is faster "
       "depends on the device)",
       tracing},
      max_structure_mb_param(),
  };
  return specs;
}

std::vector<ParamSpec> sdf_params(const std::vector<std::string>& names, const std::vector<std::string>& hits) {
  std::vector<ParamSpec> out;
  for (const std::string& name : names)
    out.push_back(name == "hit" ? with_choices(find_spec(sdf_param_specs(), name), hits, hits.front())
                                : find_spec(sdf_param_specs(), name));
  return out;
}

uint64_t max_structure_bytes(const BackendParams& params) {
  return static_cast<uint64_t>(params.integer("max_structure_mb")) << 20;
}

MeshGridParams mesh_grid_params(const BackendParams& params) {
  MeshGridParams p;
  p.cell_size = static_cast<float>(params.real("mesh_cell"));
  p.cells_per_extent = static_cast<uint32_t>(params.integer("cells_per_extent"));
  p.scale_with_triangles = !params.flag("fixed_grid");
  p.max_bytes = max_structure_bytes(params);
  return p;
}

SceneHashParams scene_hash_params(const BackendParams& params) {
  SceneHashParams p;
  p.hash_cell = static_cast<float>(params.real("hash_cell"));
  p.lists = list_rule(params.text("lists"));
  p.max_bytes = max_structure_bytes(params);
  if (params.has("octree_depth")) {
    p.octree_depth = static_cast<uint32_t>(params.integer("octree_depth"));
    p.octree_min_objects = static_cast<uint32_t>(params.integer("octree_min_objects"));
    p.octree_min_size = static_cast<float>(params.real("octree_min_size"));
  } else {
    p.octree_depth = 0;  // a backend without an octree (sdf-hash: the thesis' hash-only configuration)
  }
  return p;  // each value in its declaration's range (resolve_params); what depends on the scene: scene_hash_dims

}

SphereTraceParams trace_params(const BackendParams& params) {
  // The kernels that do not take a parameter keep the thesis' value (no over-relaxation, no cell
  // bounds, texel buffers).
  SphereTraceParams p;
  p.max_steps = static_cast<uint32_t>(params.integer("max_steps"));
  p.hit = hit_mode(params.text("hit"));
  if (params.has("hit_footprint")) p.footprint = static_cast<float>(params.real("hit_footprint"));
  if (params.has("hit_epsilon")) p.hit_epsilon = static_cast<float>(params.real("hit_epsilon"));
  if (params.has("over_relax")) p.over_relax = static_cast<float>(params.real("over_relax"));
  if (params.has("cell_bound")) p.cell_bound = params.flag("cell_bound");
  if (params.has("storage_tables")) p.storage_tables = params.flag("storage_tables");
  return p;
}

}  // namespace sdfbench::sdf
