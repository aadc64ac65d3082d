#include "renderers/sdf/triangle_distance.h"

#include <algorithm>

namespace sdfbench::sdf {
namespace {

// Closest point on segment [a, b] as a feature of the triangle: edge `edge` (1..3) whose first
// vertex is `first` (0..2); the ends are the vertex features.
TriangleClosest closest_on_edge(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b, int edge, int first) {
  const glm::vec3 ab = b - a;
  const float len2 = glm::dot(ab, ab);
  const float t = len2 > 0.0f ? glm::dot(p - a, ab) / len2 : 0.0f;
  TriangleClosest r;
  if (t <= 0.0f) {
    r.point = a;
    r.feature = kFeatureVertex0 + first;
  } else if (t >= 1.0f) {
    r.point = b;
    r.feature = kFeatureVertex0 + (first + 1) % 3;
  } else {
    r.point = a + t * ab;
    r.feature = edge;
  }
  const glm::vec3 d = p - r.point;
  r.distance_squared = glm::dot(d, d);
  return r;
}

TriangleClosest make(const glm::vec3& p, const glm::vec3& q, int feature) {
  const glm::vec3 d = p - q;
  return {q, glm::dot(d, d), feature};
}

}  // namespace

TriangleClosest closest_on_triangle(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  const glm::vec3 ab = b - a, ac = c - a, bc = c - b;
  const glm::vec3 n = glm::cross(ab, ac);
  const float longest2 = std::max({glm::dot(ab, ab), glm::dot(ac, ac), glm::dot(bc, bc)});
  // Degenerate: the closest of the three edges (ties keep the first).
  auto closest_on_edges = [&] {
    TriangleClosest best = closest_on_edge(p, a, b, kFeatureEdge01, 0);
    for (const TriangleClosest& e : {closest_on_edge(p, b, c, kFeatureEdge12, 1), closest_on_edge(p, c, a, kFeatureEdge20, 2)})
      if (e.distance_squared < best.distance_squared) best = e;
    return best;
  };
  if (glm::dot(n, n) <= 1e-12f * longest2 * longest2) return closest_on_edges();
  // Ericson 5.1.5: Voronoi regions of the vertices, then of the edges, else the face.
  const glm::vec3 ap = p - a;
  const float d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0.0f && d2 <= 0.0f) return make(p, a, kFeatureVertex0);

  const glm::vec3 bp = p - b;
  const float d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0.0f && d4 <= d3) return make(p, b, kFeatureVertex1);

  const float vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) return make(p, a + (d1 / (d1 - d3)) * ab, kFeatureEdge01);

  const glm::vec3 cp = p - c;
  const float d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0.0f && d5 <= d6) return make(p, c, kFeatureVertex2);

  const float vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) return make(p, a + (d2 / (d2 - d6)) * ac, kFeatureEdge20);

  const float va = d3 * d6 - d5 * d4;
  if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f)
    return make(p, b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * bc, kFeatureEdge12);

  const float sum = va + vb + vc;  // |n|^2 up to rounding; not positive only through underflow
  if (!(sum > 0.0f)) return closest_on_edges();
  const float denom = 1.0f / sum;
  return make(p, a + ab * (vb * denom) + ac * (vc * denom), kFeatureFace);
}

bool ray_crosses_triangle(const glm::dvec3& origin, const glm::dvec3& direction, const glm::vec3& a,
                          const glm::vec3& b, const glm::vec3& c) {
  const glm::dvec3 v0(a), e1 = glm::dvec3(b) - v0, e2 = glm::dvec3(c) - v0;
  const glm::dvec3 pv = glm::cross(direction, e2);
  const double det = glm::dot(e1, pv);
  if (det == 0.0) return false;
  const double inv = 1.0 / det;
  const glm::dvec3 tv = origin - v0;
  const double u = glm::dot(tv, pv) * inv;
  if (u < 0.0 || u > 1.0) return false;
  const glm::dvec3 qv = glm::cross(tv, e1);
  const double v = glm::dot(direction, qv) * inv;
  if (v < 0.0 || u + v > 1.0) return false;
  return glm::dot(e2, qv) * inv > 0.0;
}

}  // namespace sdfbench::sdf
