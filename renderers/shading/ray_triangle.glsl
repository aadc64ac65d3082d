// Möller & Trumbore 1997, two-sided: where the ray o + t d crosses the triangle (v0, v1, v2),
// with barycentrics uv in interpolate_barycentric's convention. One source for tri-aabb and the
// SDF backends' exact hit, in GLSL and (gpu_types.h) C++, so their hits agree with Embree's to
// rounding. Any t is returned; callers keep the range they want.
#ifndef SDFBENCH_RAY_TRIANGLE_GLSL
#define SDFBENCH_RAY_TRIANGLE_GLSL

SHARED_FN bool ray_triangle(vec3 o, vec3 d, vec3 v0, vec3 v1, vec3 v2, OUT(float) t, OUT(vec2) uv) {
  vec3 e1 = v1 - v0;
  vec3 e2 = v2 - v0;
  vec3 p = cross(d, e2);
  float det = dot(e1, p);
  if (det == 0.0f) return false;
  float inv_det = 1.0f / det;
  vec3 s = o - v0;
  float u = dot(s, p) * inv_det;
  if (u < 0.0f || u > 1.0f) return false;
  vec3 q = cross(s, e1);
  float v = dot(d, q) * inv_det;
  if (v < 0.0f || u + v > 1.0f) return false;
  t = dot(e2, q) * inv_det;
  uv = vec2(u, v);
  return true;
}

#endif
