#pragma once
// --hit exact (SphereTraceParams::hit): once sphere tracing has converged near an instance, the
// ray's crossing with the triangles its mesh grid lists there (ray_triangle.glsl, as tri-aabb),
// so t, barycentrics, normal and uv are where the ray meets the surface, as Embree's are. The
// same search as exact_crossing() in renderers/sdf_vk/sdf_exact_crossing.glsl.
#include <cstdint>

#include <glm/glm.hpp>

#include "renderers/sdf/crossing_lists.h"
#include "renderers/sdf/mesh_distance_grid.h"
#include "renderers/shading/gpu_types.h"

namespace sdfbench::sdf {

struct Crossing {
  float t = 0.0f;         // ray parameter (the same in world and object space)
  uint32_t triangle = 0;  // index in the mesh
  glm::vec2 uv{0.0f};     // barycentrics (interpolate_barycentric's convention)
};

// The earliest crossing of the ray (o + t d, in the mesh's frame) with a triangle of the mesh for
// t in [t_lo, t_hi], walking the grid cells that segment crosses and testing the triangles each
// crossing list holds: every crossing inside a cell is found there (crossing_lists.h). False
// when there is none. Adds the ray-triangle tests
// to `tests`. At most kExactMaxCells cells (SDF_EXACT_MAX_CELLS in the kernels).
constexpr uint32_t kExactMaxCells = 512;
bool exact_crossing(const MeshDistanceGrid& grid, const MeshCrossingLists& lists, const Mesh& mesh, const glm::vec3& o,
                    const glm::vec3& d, float t_lo, float t_hi, Crossing& crossing, uint32_t& tests);

}  // namespace sdfbench::sdf
