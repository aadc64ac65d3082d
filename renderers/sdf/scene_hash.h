#pragma once
// Scene level of the thesis' structure (chapters 4.2-4.3): a uniform hash grid over the scene
// whose cells hold octrees (a flat node array, thesis Algorithm 4.1 / Table 5.1) whose leaves
// list the instances that can be closest to a point inside them.
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "renderers/sdf/mesh_distance_grid.h"
#include "scenes/scene.h"

namespace sdfbench::sdf {

// Scene hash cells at most (the cell table and the octree roots are per cell).
inline constexpr uint64_t kMaxHashCells = uint64_t(1) << 26;

enum class ListRule {
  Exact,   // docs/design.md, "The SDF structures": every instance that can be the closest to some point of the region
  Thesis,  // the thesis' approximate Voronoi "influence AABB" (kept for comparison)
};

struct SceneHashParams {
  float hash_cell = 10.0f;          // --hash-cell (thesis: 10 with octree, 1 without)
  uint32_t octree_depth = 4;        // --octree-depth: 0 = hash only (4: cell 10 down to the thesis' min size 1)
  uint32_t octree_min_objects = 1;  // --octree-min-objects: a node with <= this many instances is a leaf
  float octree_min_size = 1.0f;     // --octree-min-size: a node this small (edge) is a leaf (thesis: 1)
  ListRule lists = ListRule::Exact;
  // --max-structure-mb: the build stops with an Error once the octrees' nodes and lists pass
  // this (a deep octree with a tiny min size grows without end). Not a parameter of the result.
  uint64_t max_bytes = kDefaultMaxStructureBytes;
};

struct OctreeNode {
  int32_t first_child;  // index of 8 consecutive children (octant bit 0: +x, 1: +y, 2: +z); -1: leaf
  uint32_t list_begin;  // leaf: SceneHash::instance_lists[list_begin .. list_begin + list_count)
  uint32_t list_count;
  uint32_t depth;
};

struct SceneHash {
  glm::vec3 origin{0.0f};  // min corner; cell (x, y, z) spans origin + cell_size * [x, x+1) ...
  float cell_size = 1.0f;
  glm::uvec3 dims{0};
  std::vector<uint32_t> cell_root;  // per cell (x fastest, then y, then z): its root node
  std::vector<OctreeNode> nodes;
  std::vector<uint32_t> instance_lists;
  SceneHashParams params;
  double build_ms = 0.0;

  size_t cell_count() const { return cell_root.size(); }
  size_t bytes() const;
};

struct SceneSdf;  // scene_sdf.h (included at the end): the scene hash with the mesh grids and the optional structures

void validate(const SceneHashParams& params);  // throws Error for non-positive sizes etc.
// The hash grid's cells per axis over the scene's instances; throws Error (with the real counts)
// beyond kMaxHashCells. Cheap: callers check it before the mesh grids are built.
glm::uvec3 scene_hash_dims(const Scene& scene, const SceneHashParams& params);
// One cell over all of the scene's instances, no octree, the cheap list rule: the hash of a
// structure that reads none (sdf-global; the build store's one-mesh caches), which costs next to
// nothing to build and to store at any scale.
SceneHashParams one_cell_hash(const Scene& scene, uint64_t max_bytes = kDefaultMaxStructureBytes);
// Throws Error when the scene hash, or its octrees as they grow, would pass the limits above
// (naming the flags to change); long builds print progress on stderr (util/progress.h).
SceneHash build_scene_hash(const Scene& scene, const std::vector<MeshDistanceGrid>& grids, const SceneHashParams& params);

// Distance from world point p to one instance's surface: the mesh grid distance taken in the
// instance's frame and scaled back (exact inside the mesh grid box, a lower bound outside).
float instance_distance(const SceneSdf& sdf, const Scene& scene, uint32_t instance, const glm::vec3& p,
                        uint32_t* triangle = nullptr);

struct SceneDistance {
  float distance;
  uint32_t instance;  // UINT32_MAX outside the hash box
  uint32_t triangle;
  uint32_t evaluations;  // instance distances evaluated
  // traced_scene_distance() only (traced_distance.h): the work behind the distance.
  uint32_t triangle_evaluations = 0;  // point-triangle distances
  uint32_t box_tests = 0;             // instance boxes tested to skip an instance
};

// The octree leaf holding p (thesis Algorithm 5.7); p inside the hash box (outside: the nearest cell's).
const OctreeNode& leaf_at(const SceneHash& hash, const glm::vec3& p);

// Hash cell -> octree descent -> min over the leaf's instances. Outside the hash box: the
// distance to the box (a lower bound).
SceneDistance scene_distance(const SceneSdf& sdf, const Scene& scene, const glm::vec3& p);

// Brute force over all instances (exact inside each mesh grid box): the test reference.
SceneDistance brute_force_scene_distance(const SceneSdf& sdf, const Scene& scene, const glm::vec3& p);

}  // namespace sdfbench::sdf

// SceneSdf, which most users of the scene hash read it through (it includes this header, whose
// declarations above need it only by reference).
#include "renderers/sdf/scene_sdf.h"
