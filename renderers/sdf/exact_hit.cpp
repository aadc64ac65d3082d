#include "renderers/sdf/exact_hit.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sdfbench::sdf {

bool exact_crossing(const MeshDistanceGrid& grid, const MeshCrossingLists& lists, const Mesh& mesh, const glm::vec3& o,
                    const glm::vec3& d, float t_lo, float t_hi, Crossing& crossing, uint32_t& tests) {
  constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();
  crossing.t = t_hi;
  uint32_t found = kNone;
  // The segment inside the grid box (outside it the mesh has no triangle).
  float t_cell = t_lo, t_end = t_hi;
  shading::clip_to_box(o, d, grid.origin, grid.box_max(), t_cell, t_end);
  for (uint32_t visited = 0; visited < kExactMaxCells && t_cell <= t_end; ++visited) {
    // Clamped: at the box's faces rounding can put the point a hair outside.
    const glm::uvec3 c(glm::clamp(glm::floor((o + t_cell * d - grid.origin) / grid.cell_size), glm::vec3(0.0f),
                                  glm::vec3(grid.dims - 1u)));
    const glm::vec3 cell_lo = grid.origin + glm::vec3(c) * grid.cell_size;
    float t_enter = -3.0e38f, t_exit = 3.0e38f;
    shading::clip_to_box(o, d, cell_lo, cell_lo + grid.cell_size, t_enter, t_exit);
    t_exit += 1e-5f * std::abs(t_exit);  // rounding of the cell walls
    const size_t cell = c.x + static_cast<size_t>(grid.dims.x) * (c.y + static_cast<size_t>(grid.dims.y) * c.z);
    for (uint32_t i = lists.cell_begin[cell]; i < lists.cell_begin[cell + 1]; ++i) {
      const uint32_t k = lists.triangles[i];
      const glm::uvec3 tri = mesh.triangles[k];
      float tk = 0.0f;
      glm::vec2 uv(0.0f);
      ++tests;
      if (!shading::ray_triangle(o, d, mesh.positions[tri.x], mesh.positions[tri.y], mesh.positions[tri.z], tk, uv))
        continue;
      // Ties go to the lower triangle index (the kernels walk the list in another order).
      if (tk >= t_lo && tk <= std::min(t_exit, t_hi) && (tk < crossing.t || (tk == crossing.t && k < found))) {
        crossing.t = tk;
        crossing.uv = uv;
        found = k;
      }
    }
    if (found != kNone || t_exit >= t_end) break;
    // At least a ten-thousandth of a cell: a segment starting on a cell wall at t = 0 (a shadow
    // ray leaving its surface) would otherwise pick the cell behind again and again.
    t_cell = std::max(t_exit, t_cell + std::max(1e-6f * std::abs(t_cell), 1e-4f * grid.cell_size / glm::length(d)));
  }
  crossing.triangle = found;
  return found != kNone;
}

}  // namespace sdfbench::sdf
