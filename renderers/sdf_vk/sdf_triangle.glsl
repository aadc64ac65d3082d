// Closest point on a triangle: the same branches, in the same order, as closest_on_triangle()
// in renderers/sdf/triangle_distance.cpp (Ericson, Real-Time Collision Detection 5.1.5), so
// the kernels pick the same closest triangle as the CPU reference (sdf-cpu).

vec3 closest_on_segment(vec3 p, vec3 a, vec3 b) {
  vec3 ab = b - a;
  float len2 = dot(ab, ab);
  float t = len2 > 0.0f ? dot(p - a, ab) / len2 : 0.0f;
  if (t <= 0.0f) return a;
  if (t >= 1.0f) return b;
  return a + t * ab;
}

float distance_squared(vec3 p, vec3 q) {
  vec3 d = p - q;
  return dot(d, d);
}

// Degenerate triangles count as their three edges; ties keep the first edge.
vec3 closest_on_edges(vec3 p, vec3 a, vec3 b, vec3 c) {
  vec3 best = closest_on_segment(p, a, b);
  vec3 e = closest_on_segment(p, b, c);
  if (distance_squared(p, e) < distance_squared(p, best)) best = e;
  e = closest_on_segment(p, c, a);
  if (distance_squared(p, e) < distance_squared(p, best)) best = e;
  return best;
}

vec3 closest_on_triangle(vec3 p, vec3 a, vec3 b, vec3 c) {
  vec3 ab = b - a, ac = c - a, bc = c - b;
  vec3 n = cross(ab, ac);
  float longest2 = max(max(dot(ab, ab), dot(ac, ac)), dot(bc, bc));
  if (dot(n, n) <= 1e-12f * longest2 * longest2) return closest_on_edges(p, a, b, c);
  vec3 ap = p - a;
  float d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0.0f && d2 <= 0.0f) return a;
  vec3 bp = p - b;
  float d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0.0f && d4 <= d3) return b;
  float vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) return a + (d1 / (d1 - d3)) * ab;
  vec3 cp = p - c;
  float d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0.0f && d5 <= d6) return c;
  float vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) return a + (d2 / (d2 - d6)) * ac;
  float va = d3 * d6 - d5 * d4;
  if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f) return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * bc;
  float sum = va + vb + vc;  // |n|^2 up to rounding; not positive only through underflow
  if (!(sum > 0.0f)) return closest_on_edges(p, a, b, c);
  float denom = 1.0f / sum;
  return a + ab * (vb * denom) + ac * (vc * denom);
}

// Barycentric (u, v) of a point of triangle abc, p = (1 - u - v) a + u b + v c: as
// barycentric() in renderers/sdf/sphere_tracer.cpp.
vec2 barycentric(vec3 p, vec3 a, vec3 b, vec3 c) {
  vec3 v0 = b - a, v1 = c - a, v2 = p - a;
  float d00 = dot(v0, v0), d01 = dot(v0, v1), d11 = dot(v1, v1);
  float d20 = dot(v2, v0), d21 = dot(v2, v1);
  float denom = d00 * d11 - d01 * d01;
  if (denom == 0.0f) return vec2(0.0f);
  return vec2((d11 * d20 - d01 * d21) / denom, (d00 * d21 - d01 * d20) / denom);
}
