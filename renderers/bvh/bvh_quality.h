#pragma once
// How good a BVH is, as the literature measures it, for the whole structure the kernel traverses
// (both levels, in world space; an instance's nodes count at their world size, object-space areas
// times the instance's scale squared):
// - SAH cost (MacDonald & Booth 1990): sum over node visits of C_t * A(node) / A(root), plus
//   C_i * triangles * A(leaf) / A(root); C_t = C_i = 1, the root visit included.
// - EPO, end-point overlap (Aila, Karras & Laine 2013, "On quality metrics of bounding volume
//   hierarchies"): sum over nodes of C(node) * A(geometry inside the node's box but not in its
//   subtree) / A(all geometry); C = C_t for an inner node (and a top-level entry), C_i * its
//   triangles for a leaf. Estimated from `samples` points spread uniformly over the triangles'
//   area (seeded, so a structure always reports the same figure), since the exact sum clips every
//   triangle against every box; bvh_epo_exact does that, for small scenes and the tests.
#include <cstdint>

#include "renderers/bvh/bvh_scene.h"
#include "scenes/scene.h"

namespace sdfbench {

struct BvhQuality {
  double sah = 0;
  double epo = 0;
  uint64_t nodes = 0;    // inner nodes of both levels
  uint64_t entries = 0;  // top-level entries (instances, or more when rebraided; 0 when flat)
};

double bvh_sah(const BvhScene& bvh, const Scene& scene);
double bvh_epo(const BvhScene& bvh, const Scene& scene, uint32_t samples = 16384, uint64_t seed = 1);
double bvh_epo_exact(const BvhScene& bvh, const Scene& scene);
BvhQuality bvh_quality(const BvhScene& bvh, const Scene& scene);

}  // namespace sdfbench
