#include "renderers/sdf/crossing_lists.h"

#include <limits>
#include <string>

#include "util/error.h"

namespace sdfbench::sdf {

MeshCrossingLists make_crossing_lists(const MeshDistanceGrid& grid, const Mesh& mesh) {
  const size_t cells = grid.cell_count();
  // Far beyond the rounding of a cell lookup near its walls (the walk's own slack is 1e-5 t).
  const float slack = 1e-3f * grid.cell_size;
  const glm::vec3 top(grid.dims - 1u);
  auto for_each_cell = [&](auto&& visit) {
    for (uint32_t k = 0; k < mesh.triangles.size(); ++k) {
      const glm::uvec3& t = mesh.triangles[k];
      const glm::vec3 a = glm::min(glm::min(mesh.positions[t[0]], mesh.positions[t[1]]), mesh.positions[t[2]]) - slack;
      const glm::vec3 b = glm::max(glm::max(mesh.positions[t[0]], mesh.positions[t[1]]), mesh.positions[t[2]]) + slack;
      const glm::uvec3 lo(glm::clamp(glm::floor((a - grid.origin) / grid.cell_size), glm::vec3(0.0f), top));
      const glm::uvec3 hi(glm::clamp(glm::floor((b - grid.origin) / grid.cell_size), glm::vec3(0.0f), top));
      for (uint32_t z = lo.z; z <= hi.z; ++z)
        for (uint32_t y = lo.y; y <= hi.y; ++y)
          for (uint32_t x = lo.x; x <= hi.x; ++x) visit(x + size_t(grid.dims.x) * (y + size_t(grid.dims.y) * z), k);
    }
  };
  std::vector<uint64_t> begin(cells + 1, 0);
  for_each_cell([&](size_t c, uint32_t) { ++begin[c + 1]; });
  for (size_t c = 0; c < cells; ++c) begin[c + 1] += begin[c];
  if (begin[cells] >= std::numeric_limits<uint32_t>::max())
    throw Error("the exact-hit lists of mesh '" + mesh.name + "' have " + std::to_string(begin[cells]) +
                " entries, more than 32-bit indices allow; use a larger --mesh-cell or fewer --cells-per-extent");
  MeshCrossingLists lists;
  lists.triangles.resize(begin[cells]);
  lists.cell_begin.assign(begin.begin(), begin.end());
  std::vector<uint64_t> next(begin.begin(), begin.end() - 1);
  for_each_cell([&](size_t c, uint32_t k) { lists.triangles[next[c]++] = k; });
  return lists;
}

}  // namespace sdfbench::sdf
