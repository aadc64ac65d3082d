#pragma once
// The SDF structures (mesh distance grids, scene hash + octrees) flattened into the arrays the
// sdf-hash / sdf-octree kernels read; the layout is documented in sdf_layout.glsl.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "renderers/sdf/scene_hash.h"
#include "renderers/sdf/sphere_tracer.h"
#include "scenes/scene.h"

namespace sdfbench {
namespace shading {
using namespace glm;
#include "sdf_layout.glsl"
}  // namespace shading

struct SdfGpuArrays {
  shading::SdfParams params;
  std::vector<uint32_t> hash_cells;      // node word per hash cell
  std::vector<uint32_t> octree_nodes;    // node words below the roots
  std::vector<uint32_t> instance_lists;  // per leaf: count, then instances
  std::vector<glm::uvec4> instance_records, mesh_records;
  std::vector<glm::uvec2> grid_cells;    // (begin, end) list entries
  std::vector<glm::vec4> grid_entries;   // SDF_ENTRY_TEXELS per list entry, each cell's nearest first
  // The exact hits' lists (renderers/sdf/crossing_lists.h): per grid cell (indexed as grid_cells)
  // the (begin, end) of its entries in crossing_triangles, each a global triangle index.
  std::vector<glm::uvec2> crossing_cells;
  std::vector<uint32_t> crossing_triangles;
  std::vector<glm::vec4> vertices, normals;  // 3 per global triangle
};

// How a leaf's instance list is stored: as built (the list's second word is --cell-bound's bound),
// or (sdf-bricks) the same instances with those whose box meets the leaf's box first and their
// count in the second word.
enum class LeafLists { as_built, overlapping_first };

// Throws Error when an index would not fit the 31-bit node words.
SdfGpuArrays flatten_for_gpu(const Scene& scene, const sdf::SceneSdf& sdf, const sdf::SphereTraceParams& tracing,
                             LeafLists leaf_lists = LeafLists::as_built);

}  // namespace sdfbench
