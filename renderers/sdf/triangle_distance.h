#pragma once
// Point-triangle distance (the building block of every SDF structure) and a ray-triangle
// crossing test (the independent inside/outside check of `sdfbench check-sdf`).
#include <glm/glm.hpp>

namespace sdfbench::sdf {

// Feature codes of TriangleClosest::feature.
enum TriangleFeature : int {
  kFeatureFace = 0,
  kFeatureEdge01 = 1,  // edges: 1 + k is the edge from vertex k to vertex (k + 1) % 3
  kFeatureEdge12 = 2,
  kFeatureEdge20 = 3,
  kFeatureVertex0 = 4,  // vertices: 4 + k is vertex k
  kFeatureVertex1 = 5,
  kFeatureVertex2 = 6,
};

// Closest point on triangle (Ericson, Real-Time Collision Detection 5.1.5) and which feature it lies on.
struct TriangleClosest {
  glm::vec3 point;
  float distance_squared;
  int feature;  // 0 face, 1..3 edge (v0v1, v1v2, v2v0), 4..6 vertex v0..v2
};

// Exact up to float rounding for every triangle. Degenerate triangles (collinear or coincident
// vertices, |cross(b - a, c - a)|^2 <= 1e-12 * longest_edge^4) are treated as their three edges,
// so the result is never a face point and never NaN.
TriangleClosest closest_on_triangle(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c);

// Whether the ray origin + t * direction, t > 0, crosses triangle abc (Moeller-Trumbore in
// double precision; the ray parity test counts these). Degenerate triangles are never crossed.
bool ray_crosses_triangle(const glm::dvec3& origin, const glm::dvec3& direction, const glm::vec3& a,
                          const glm::vec3& b, const glm::vec3& c);

}  // namespace sdfbench::sdf
