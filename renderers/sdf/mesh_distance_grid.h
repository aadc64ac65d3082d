#pragma once
// The per-mesh exact distance grid (docs/design.md, "The SDF structures"; thesis 5.1): a uniform grid
// around one mesh whose every cell lists the triangles that can be the closest one to some point
// of the cell, so that inside the grid the minimum over a cell's list *is* the unsigned distance
// to the mesh (not the thesis' heuristic approximation). Built once per mesh, shared by all of
// the mesh's instances.
//
// Default resolution: 32 cells along the mesh's largest extent, plus one margin cell per side
// (27x34x34 cells for the bunny). Measured with `check-sdf` on the bunny (tight rule, S = 2):
//   16/extent:   4860 cells, mean list 52, 1.3 MB, build 0.2 s
//   32/extent:  31212 cells, mean list 19, 2.8 MB, build 0.6 s
//   64/extent: 218790 cells, mean list 8.6, 8.6 MB, build 3.6 s
// (2 cores). Each sphere-tracing step costs one point-triangle distance per list entry, so finer
// grids trace faster, but every doubling costs ~7x the cells and ~6x the build for a ~2.3x
// shorter list. 32 keeps the build under a second and the grid a few MB per mesh (the same order
// as the thesis' grids); 64 is worth trying per benchmark (cells_per_extent or cell_size, and
// `check-sdf --cells-per-extent`), not as a default for every mesh.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "renderers/backend_params.h"
#include "renderers/sdf/triangle_distance.h"
#include "scenes/mesh.h"

namespace sdfbench::sdf {

// Which test decides that a triangle cannot be closest to any point of a cell (both exact, proofs
// in the .cpp). Mean list lengths at 32/extent, bunny/teapot/monkey/sphere: sphere 118/154/39/25,
// tight with S = 1: 28/35/11/6.8, S = 2: 19/22/8.3/5.5, S = 3: 17/19/7.7/5.1.
enum class MeshGridRule {
  tight,   // separating-axis bounds against the cell's (and its sub-boxes') corner reach (default)
  sphere,  // dist(T, centre) <= d_c + 2h only: docs/design.md's cheap rule, kept for comparison
};

// kDefaultMaxStructureBytes (renderers/backend_params.h): the default memory cap of one SDF
// structure (a mesh grid's cell lists, the scene hash's octrees), --max-structure-mb. The Vulkan
// backends' 31-bit words and the 4 GiB cache sit beyond it.

// Large meshes (the mesh-size axis): a fixed resolution would put ever more triangles in every
// cell, so beyond kScaledGridFromTriangles the cells per extent grow as sqrt(triangles) (a
// surface's cells grow as the square of the resolution, so triangles per surface cell stay
// about what they are at the threshold), up to kMaxScaledCellsPerExtent; and cells two or more
// cells (Chebyshev) from every cell a triangle's bounding box touches hold a lower bound
// instead of a list (far cells: their lists would be the longest, no query there needs the
// exact distance to step safely, and the bound needs no nearest-triangle search per cell).
// The thesis meshes (768-4968 triangles) are below the threshold: unchanged.
inline constexpr size_t kScaledGridFromTriangles = 8192;
inline constexpr uint32_t kMaxScaledCellsPerExtent = 256;

struct MeshGridParams {
  float cell_size = 0.0f;          // > 0: explicit cell size (mesh units); 0: derived from cells_per_extent
  uint32_t cells_per_extent = 32;  // cells along the mesh's largest bounding-box extent
  float margin_cells = 1.0f;       // grid box = mesh bounds grown by this many cells on every side
  MeshGridRule rule = MeshGridRule::tight;
  uint32_t subdivision = 2;        // tight rule: also test each cell's S^3 sub-boxes (1..8; exact for any S)
  // --max-structure-mb: the build stops with an Error once the cell lists pass this. Not a
  // parameter of the result (caches and result keys leave it out).
  uint64_t max_bytes = kDefaultMaxStructureBytes;
  bool scale_with_triangles = true;  // the rule above (--fixed-grid: off); only with cells_per_extent
};

// The exact grid (docs/design.md, "The SDF structures"): each cell lists every triangle that can be the closest one to some point of the cell.
struct MeshDistanceGrid {
  glm::vec3 origin{0.0f};  // min corner of the grid box
  float cell_size = 0.0f;
  glm::uvec3 dims{0u};     // cells per axis; cell (x, y, z) is x + dims.x * (y + dims.y * z)
  std::vector<uint32_t> cell_begin;  // CSR: cell i lists triangles[cell_begin[i] .. cell_begin[i+1])
  std::vector<uint32_t> cell_triangles;  // each cell's list ascending by triangle index
  // sign: angle-weighted pseudo-normals (Baerentzen & Aanaes 2005) per face, per edge (3 per
  // triangle, edge k of triangle t at 3t + k) and per vertex (indexed like mesh.positions).
  // Vertices at identical positions are welded first, so split seams do not break the sign.
  std::vector<glm::vec3> face_normals, edge_normals, vertex_normals;
  // Scaled grids only (else empty): per cell 0 for a listed cell, else a far cell's bound: its
  // centre's distance to the mesh (rounded down), negative inside. A far cell's list is empty.
  std::vector<float> far_distance;
  std::vector<float> far_upper;  // per cell: an upper bound on a far cell's centre distance (CPU only: the scene hash's lists)
  double build_ms = 0;

  size_t bytes() const;  // payload: the CSR arrays and the pseudo-normals
  // Whether `cell` is a far cell (a bound, no list), and how many there are.
  bool is_far(size_t cell) const { return !far_distance.empty() && far_distance[cell] != 0.0f; }
  size_t far_cell_count() const;
  size_t cell_count() const { return static_cast<size_t>(dims.x) * dims.y * dims.z; }
  glm::vec3 box_max() const { return origin + glm::vec3(dims) * cell_size; }
};

// The cells per extent a build uses for `triangles` (the rule above; the requested value when
// it does not apply), and whether it makes far cells.
uint32_t effective_cells_per_extent(const MeshGridParams& params, size_t triangles);
bool has_far_cells(const MeshGridParams& params, size_t triangles);

// Where a build puts the mesh's grid: its cell size (from the mesh's bounds and the parameters),
// cells per axis and origin (centred on the mesh). Throws Error for a grid over 2^26 cells. A
// cache's grid is checked against it (a cache resealed with changed values).
struct MeshGridLayout {
  glm::vec3 origin{0.0f};
  float cell_size = 0.0f;
  glm::uvec3 dims{0u};
};
MeshGridLayout mesh_grid_layout(const Mesh& mesh, const MeshGridParams& params);

// Throws Error for unusable parameters (non-positive or non-finite cell size, zero cells per
// extent, negative margin, subdivision outside 1..8), a grid over 2^26 cells, or lists passing
// params.max_bytes (checked as they grow). Prints progress on stderr when the build is long.
MeshDistanceGrid build_mesh_distance_grid(const Mesh& mesh, const MeshGridParams& params);

// Unsigned distance: inside the grid box the min over the cell's listed triangles (exact); in a
// far cell its bound less the distance from its centre (a lower bound, >= 0.63 cells);
// outside, the distance to the mesh bounds (a safe lower bound, >= the distance to the grid
// box). closest_triangle set in listed cells (kFarCellTriangle in far cells, else UINT32_MAX).
float grid_distance(const MeshDistanceGrid& grid, const Mesh& mesh, const glm::vec3& p, uint32_t* closest_triangle = nullptr);

// The closest triangle grid_distance reports in a far cell: none, and the tracers step by the
// bound itself (a bound below the hit epsilon is common there, and a step of at least an
// epsilon could cross a surface the bound does not see; the bound, >= 0.63 cells, never stalls).
inline constexpr uint32_t kFarCellTriangle = UINT32_MAX - 1;

// Whether p is in a far cell of a scaled grid (there grid_distance is a bound, not exact).
bool in_far_cell(const MeshDistanceGrid& grid, const glm::vec3& p);
// An upper bound on the distance at p inside the grid box: grid_distance (exact) in listed
// cells, a far cell's upper bound plus the way from its centre in far cells.
float grid_upper_distance(const MeshDistanceGrid& grid, const Mesh& mesh, const glm::vec3& p);

// A grid's lists as the sphere tracers walk them (sdf-cpu and the Vulkan kernels alike): each cell's
// triangles nearest to the cell centre first, so that a query finds a close triangle early and
// stops at the first entry whose distance from the centre, less the point's, exceeds the best:
// dist(p, T) >= dist(c, T) - |p - c|, and the entries after it are farther from c still. (A
// bounding-sphere test per entry before it cost more than it saved: 13 % slower on lavapipe.)
struct MeshTraceLists {
  std::vector<uint32_t> triangles;       // cell_triangles reordered within each cell (ties: lower index first)
  std::vector<float> centre_distances;   // per entry: dist(cell centre, triangle), rounded down
};
// How far make_trace_lists rounds a centre distance down, in cells: far beyond float rounding of
// the distance and of |p - c| (both a few 1e-7 of the grid's extent), far below a step.
inline constexpr float kCentreDistanceSlackCells = 1e-4f;
// Whether the list entries from one with `centre_distance` on can all be skipped at a point
// `from_centre` from its cell's centre, the best squared distance so far being `best` (the
// kernels' test, sdf_scene_distance.glsl, is the same).
inline bool past_the_best(float centre_distance, float from_centre, float best) {
  const float lower = centre_distance - from_centre;
  return lower > 0.0f && lower * lower > best * 1.0001f;
}
MeshTraceLists make_trace_lists(const MeshDistanceGrid& grid, const Mesh& mesh);

// grid_distance() through `lists`, stopping at past_the_best(): the same distance and closest
// triangle, less work. Adds the point-triangle distances it computed to `evaluated`.
float traced_grid_distance(const MeshDistanceGrid& grid, const Mesh& mesh, const MeshTraceLists& lists,
                           const glm::vec3& p, uint32_t& closest_triangle, uint32_t& evaluated);

// Signed distance (negative inside) for points inside the grid box, sign from the pseudo-normal of
// the closest feature (correct for closed, consistently oriented meshes). Outside the grid box
// (which contains the whole mesh) the point is outside: the positive box lower bound.
float grid_signed_distance(const MeshDistanceGrid& grid, const Mesh& mesh, const glm::vec3& p);

// Exact distances anywhere, for the brick and global fields' samples: the grid's in its box (a
// far cell's bound there, as grid_distance), beyond the box, where the grid gives only a bound, a
// nearest-triangle query over a BVH of the mesh's triangles, signed by the grid's pseudo-normals
// as in the box (ties: the lowest triangle index, as a cell's ascending list gives). It replaced a
// wider grid built for the sampling: the band beyond the box holds few samples, while a grid up to
// 16 cells wider on every side has many more cells to list (a 32x18 sdf-global render of fig6_3:
// 16.8 s -> 4.3 s, sdf-bricks 7.1 s -> 4.5 s). The grid and mesh must outlive it.
class ExactMeshDistance {
 public:
  ExactMeshDistance(const MeshDistanceGrid& grid, const Mesh& mesh);
  ~ExactMeshDistance();
  ExactMeshDistance(ExactMeshDistance&&) noexcept;
  ExactMeshDistance& operator=(ExactMeshDistance&&) noexcept;
  // Beyond the box, a surface farther than `bound` is not searched for: the answer is then
  // +infinity (callers clamp to a band or take a minimum); at or within `bound` it is exact.
  float distance(const glm::vec3& p, float bound = std::numeric_limits<float>::infinity()) const;
  float signed_distance(const glm::vec3& p, float bound = std::numeric_limits<float>::infinity()) const;

 private:
  float nearest(const glm::vec3& p, float bound, uint32_t& triangle) const;
  struct Tree;
  const MeshDistanceGrid* grid_;
  const Mesh* mesh_;
  std::unique_ptr<Tree> tree_;
};

// Brute force over all triangles: the independent reference.
float brute_force_distance(const Mesh& mesh, const glm::vec3& p, uint32_t* closest_triangle = nullptr);

// Edges (after welding equal positions) not shared by exactly two triangles; 0 for a closed mesh.
size_t open_edge_count(const Mesh& mesh);

// Inside by ray parity, brute force over all triangles: the majority of three fixed, skew ray
// directions (an independent check of the pseudo-normal sign; meaningful for closed meshes).
bool ray_parity_inside(const Mesh& mesh, const glm::vec3& p);

}  // namespace sdfbench::sdf
