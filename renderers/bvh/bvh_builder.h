#pragma once
// A binary BVH built by Embree's BVH builder (rtcBuildBVH: SAH, and at RTC_BUILD_QUALITY_HIGH
// spatial splits as in Stich et al. 2009, "Spatial splits in bounding volume hierarchies") and
// flattened depth-first into the node layout of Aila & Laine 2009, "Understanding the efficiency
// of ray traversal on GPUs": an inner node holds both children's boxes, so one fetch lets the
// traversal test both children and descend into the nearer first.
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "renderers/embree/embree_api.h"
#include "scenes/aabb.h"
#include "scenes/mesh.h"

namespace sdfbench {

// One inner node, 4 texels (bvh.comp reads it so). A child is an inner node (count 0: `child` is
// its node index) or a leaf (`child` is its first reference, `count` references); an empty child
// is a point box at (FLT_MAX, FLT_MAX, FLT_MAX), which no ray reaches. (Not an inverted box: the
// slab test swaps a slab's ends, so an inverted box would look like all of space.)
struct BvhNode {
  glm::vec4 left_min;   // xyz; w: the left child (uint bits)
  glm::vec4 left_max;   // xyz; w: the right child
  glm::vec4 right_min;  // xyz; w: the left child's reference count (0: an inner node)
  glm::vec4 right_max;  // xyz; w: the right child's reference count
};

struct FlatBvh {
  std::vector<BvhNode> nodes;        // nodes[0]: the root (an inner node, also for 0 or 1 primitives)
  std::vector<uint32_t> references;  // leaf contents, leaf after leaf: primitive ids (spatial splits repeat some)
  uint32_t depth = 0;                // inner nodes on the longest root-to-leaf path
};

struct BvhBuildParams {
  RTCBuildQuality quality = RTC_BUILD_QUALITY_HIGH;
  unsigned max_leaf_size = 4;
  // Embree's limit; it makes large leaves 8 levels above it, so only a pathological scene reaches
  // it (rtcBuildBVH then fails).
  unsigned max_depth = 64;
  float traversal_cost = 1.0f;
  float intersection_cost = 1.0f;
};

// Clips primitive `id`'s part inside `part` at the plane x[dimension] = position into the parts
// on either side (spatial splits).
using SplitPrimitive = std::function<void(uint32_t id, const Aabb& part, unsigned dimension, float position,
                                          Aabb& left, Aabb& right)>;

// boxes[i]: primitive i's bounds. Without `split`, primitives are never split.
FlatBvh build_bvh(RTCDevice device, const std::vector<Aabb>& boxes, const BvhBuildParams& params,
                  const SplitPrimitive& split = {});

// Spatial splits of triangles: the bounds of the triangle's part on either side, within `part`.
void split_triangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const Aabb& part, unsigned dimension,
                    float position, Aabb& left, Aabb& right);

// A mesh's BVH over its triangles, split spatially (the mesh must outlive the call only).
FlatBvh build_mesh_bvh(RTCDevice device, const Mesh& mesh, const BvhBuildParams& params);

}  // namespace sdfbench
