#include "renderers/sdf_global/triangle_box_overlap.h"

#include <algorithm>
#include <cmath>

namespace sdfbench::sdf {
namespace {

// The projections of the triangle's vertices (box-centred) and the box on `axis` do not meet.
bool separated_on(const glm::vec3& axis, const glm::vec3& v0, const glm::vec3& v1, const glm::vec3& v2,
                  const glm::vec3& half) {
  const float p0 = glm::dot(axis, v0), p1 = glm::dot(axis, v1), p2 = glm::dot(axis, v2);
  const float r = half.x * std::abs(axis.x) + half.y * std::abs(axis.y) + half.z * std::abs(axis.z);
  return std::min({p0, p1, p2}) > r || std::max({p0, p1, p2}) < -r;
}

}  // namespace

bool triangle_meets_box(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& centre,
                        const glm::vec3& half) {
  const glm::vec3 v0 = a - centre, v1 = b - centre, v2 = c - centre;
  // The box's axes: the triangle's bounds against the box.
  for (int k = 0; k < 3; ++k)
    if (std::min({v0[k], v1[k], v2[k]}) > half[k] || std::max({v0[k], v1[k], v2[k]}) < -half[k]) return false;
  const glm::vec3 edges[3] = {v1 - v0, v2 - v1, v0 - v2};
  // The triangle's plane (a degenerate triangle has none; its edges' axes still apply).
  const glm::vec3 normal = glm::cross(edges[0], edges[1]);
  if (glm::dot(normal, normal) > 0.0f && separated_on(normal, v0, v1, v2, half)) return false;
  // Edge x box axis.
  for (const glm::vec3& e : edges)
    for (int k = 0; k < 3; ++k) {
      glm::vec3 unit(0.0f);
      unit[k] = 1.0f;
      const glm::vec3 axis = glm::cross(e, unit);
      if (glm::dot(axis, axis) > 0.0f && separated_on(axis, v0, v1, v2, half)) return false;
    }
  return true;
}

}  // namespace sdfbench::sdf
