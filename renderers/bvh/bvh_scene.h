#pragma once
// The scene's BVHs as bvh.comp traverses them, before any GPU layout (--bvh-top):
// - instanced: every mesh's BVH once, and a top level over the instances' world boxes, one
//   instance a leaf (the classic two-level BVH);
// - rebraided: the top level over entries, each an instance and a node of its mesh's BVH: the
//   instances' roots opened into their children, largest world-space surface area first, until the
//   top level holds --bvh-rebraid entries per instance (partial re-braiding, Benthin, Woop, Wald &
//   Áfra 2017, "Improved two-level BVHs using partial re-braiding": where instances overlap, a ray
//   no longer enters every overlapping instance whose box it crosses);
// - flat: one BVH over every instance's triangles in world space (a single level; memory grows
//   with the instances, so it is refused beyond --max-structure-mb).
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "renderers/bvh/bvh_builder.h"
#include "renderers/bvh/bvh_tree.h"
#include "scenes/mesh.h"
#include "scenes/scene.h"

namespace sdfbench {

enum class BvhTop { Instanced, Rebraided, Flat };

struct BvhSceneParams {
  uint32_t width = 2;
  BvhTop top = BvhTop::Instanced;
  double rebraid = 2;  // rebraided: top-level entries per instance (at least 1)
  uint64_t max_bytes = uint64_t(2048) << 20;  // flat: the cap on its world-space triangles (--max-structure-mb)
};

// A top-level reference: an instance and an inner node of its mesh's BVH (BvhTree numbering).
struct BvhEntry {
  uint32_t instance = 0;
  uint32_t node = 0;
};

// A triangle of the flat tree: where it came from.
struct FlatTriangle {
  uint32_t instance = 0, prim = 0, material = 0;
};

struct BvhScene {
  BvhTop top_kind = BvhTop::Instanced;
  BvhTree top;                     // two levels: references are entries; flat: triangles of flat_mesh()
  std::vector<BvhEntry> entries;   // two levels
  std::vector<BvhTree> meshes;     // two levels: per scene mesh
  // flat: the scene of the triangle tables, one mesh (every instance's triangles in world space)
  // and one identity instance; flat_triangles says where each triangle came from.
  Scene flat_world;
  std::vector<FlatTriangle> flat_triangles;
  const Mesh& flat_mesh() const { return flat_world.meshes.front(); }
};

// Mesh and top-level build settings (measured on lavapipe, bvh_renderer.cpp).
BvhBuildParams bvh_mesh_build(uint32_t width);
BvhBuildParams bvh_top_build(uint32_t width);

// The bytes the flat tree's world-space tables take for `scene` (checked before it is built).
uint64_t flat_bvh_bytes(const Scene& scene);

BvhScene build_bvh_scene(RTCDevice device, const Scene& scene, const BvhSceneParams& params);

}  // namespace sdfbench
