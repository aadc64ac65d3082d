#pragma once
// The exact hits' triangle lists (exact_hit.h, sdf_exact_crossing.glsl): per mesh-grid cell the
// triangles whose bounding box, grown by a rounding slack, meets the cell. Every point of a
// triangle inside a cell lies in such a box, so a ray's crossing inside a cell is found among
// them. The grid's own lists (the triangles nearest to the cell's points, for distances) hold
// these too, and more (thesis:bunny:1000 primary, sdf-global: 93 -> 10 ray-triangle tests per ray).
#include <cstdint>
#include <vector>

#include "renderers/sdf/mesh_distance_grid.h"
#include "scenes/mesh.h"

namespace sdfbench::sdf {

struct MeshCrossingLists {
  std::vector<uint32_t> cell_begin;  // per cell + 1 (x fastest): cell c's triangles are triangles[begin[c] .. begin[c+1])
  std::vector<uint32_t> triangles;   // indices into the mesh, ascending within a cell
};

// Throws Error when the lists would not fit 32-bit indices (naming the flags that shrink them).
MeshCrossingLists make_crossing_lists(const MeshDistanceGrid& grid, const Mesh& mesh);

}  // namespace sdfbench::sdf
