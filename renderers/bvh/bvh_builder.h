#pragma once
// A BVH of 2 to 8 children a node built by Embree's BVH builder (rtcBuildBVH: SAH, and at
// RTC_BUILD_QUALITY_HIGH spatial splits as in Stich et al. 2009, "Spatial splits in bounding
// volume hierarchies"; a wide node is made as Embree makes its BVH4/BVH8, opening the child of
// largest surface area), flattened depth-first into a BvhTree (bvh_tree.h).
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "renderers/bvh/bvh_tree.h"
#include "renderers/embree/embree_api.h"
#include "scenes/aabb.h"
#include "scenes/mesh.h"

namespace sdfbench {

struct BvhBuildParams {
  RTCBuildQuality quality = RTC_BUILD_QUALITY_HIGH;
  unsigned width = 2;  // children a node: 2..kMaxBvhWidth (Embree's builder opens the largest child, by SAH)
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
BvhTree build_bvh(RTCDevice device, const std::vector<Aabb>& boxes, const BvhBuildParams& params,
                  const SplitPrimitive& split = {});

// Spatial splits of triangles: the bounds of the triangle's part on either side, within `part`.
void split_triangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const Aabb& part, unsigned dimension,
                    float position, Aabb& left, Aabb& right);

// A mesh's BVH over its triangles, split spatially (the mesh must outlive the call only).
BvhTree build_mesh_bvh(RTCDevice device, const Mesh& mesh, const BvhBuildParams& params);

}  // namespace sdfbench
