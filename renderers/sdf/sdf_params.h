#pragma once
// The SDF backends' shared parameters (the thesis' structure and sphere tracing), declared once
// (renderers/backend_params.h), and the structures' parameter records made from a backend's
// resolved values. Each SDF backend owns the subset it reads (its declaration names them).
#include <string>
#include <vector>

#include "renderers/backend_params.h"
#include "renderers/sdf/mesh_distance_grid.h"
#include "renderers/sdf/scene_hash.h"
#include "renderers/sdf/sphere_tracer.h"

namespace sdfbench::sdf {

// hash_cell, octree_depth, octree_min_objects, octree_min_size, lists, mesh_cell, cells_per_extent,
// fixed_grid, hit, max_steps, hit_epsilon, hit_footprint, over_relax, cell_bound, storage_tables,
// max_structure_mb: their specs, in CSV column order.
const std::vector<ParamSpec>& sdf_param_specs();
// The specs named (a backend's subset), its --hit limited to `hits` (exact distances: exact or
// thesis; sampled fields: exact or field), the first of them its default.
std::vector<ParamSpec> sdf_params(const std::vector<std::string>& names, const std::vector<std::string>& hits);

// The records the builders and tracers take, from a backend's resolved parameters (their typed
// values, each already checked against its declaration by resolve_params: no range is checked
// again here). Each reads only the parameters its record holds; a backend that does not own one of
// them gets its default (scene_hash_params of a backend without an octree: depth 0).
MeshGridParams mesh_grid_params(const BackendParams& params);
SceneHashParams scene_hash_params(const BackendParams& params);
SphereTraceParams trace_params(const BackendParams& params);
uint64_t max_structure_bytes(const BackendParams& params);

}  // namespace sdfbench::sdf
