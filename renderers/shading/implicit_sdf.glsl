// Signed distances and generated uv of the implicit primitives (thesis 5.1 and Algorithms 3.2,
// 5.1-5.3; Quilez's formulas), each in the primitive's own frame: negative inside. Pure
// functions shared by the GLSL kernels and C++ (gpu_types.h), so tests call them directly.
// Parameters (GpuImplicitNode a, b): sphere a.x radius; box a.xyz half extents, a.w rounding;
// ellipsoid a.xyz radii; capsule a.xyz, b.xyz end points, a.w radius; torus a.x major,
// a.y minor radius, about the y axis; plane a.xyz unit normal, a.w offset (inside: below it).
#ifndef SDFBENCH_IMPLICIT_SDF_GLSL
#define SDFBENCH_IMPLICIT_SDF_GLSL

#define IMPLICIT_TWO_PI 6.28318530718f

// Box with rounded edges: the half extents include the rounding.
SHARED_FN float sdf_box(vec3 q, vec3 half_extents, float rounding) {
  vec3 d = abs(q) - half_extents + rounding;
  return length(max(d, vec3(0.0f))) + min(max(d.x, max(d.y, d.z)), 0.0f) - rounding;
}

// Quilez's ellipsoid distance: exact on the axes and on the surface, close elsewhere (no closed
// form exists). The centre, where it is 0/0, is -(smallest radius), the exact value.
SHARED_FN float sdf_ellipsoid(vec3 q, vec3 radii) {
  float k0 = length(q / radii);
  float k1 = length(q / (radii * radii));
  return k1 > 0.0f ? k0 * (k0 - 1.0f) / k1 : -min(radii.x, min(radii.y, radii.z));
}

SHARED_FN float sdf_capsule(vec3 q, vec3 a, vec3 b, float radius) {
  vec3 pa = q - a, ba = b - a;
  float len2 = dot(ba, ba);
  float h = len2 > 0.0f ? clamp(dot(pa, ba) / len2, 0.0f, 1.0f) : 0.0f;
  return length(pa - ba * h) - radius;
}

SHARED_FN float sdf_torus(vec3 q, float major, float minor) {
  return length(vec2(length(vec2(q.x, q.z)) - major, q.y)) - minor;
}

SHARED_FN float implicit_primitive_distance(uint kind, vec4 a, vec4 b, vec3 q) {
  if (kind == IMPLICIT_SPHERE) return length(q) - a.x;
  if (kind == IMPLICIT_BOX) return sdf_box(q, vec3(a), a.w);
  if (kind == IMPLICIT_ELLIPSOID) return sdf_ellipsoid(q, vec3(a));
  if (kind == IMPLICIT_CAPSULE) return sdf_capsule(q, vec3(a), vec3(b), a.w);
  if (kind == IMPLICIT_TORUS) return sdf_torus(q, a.x, a.y);
  return dot(q, vec3(a)) - a.w;  // IMPLICIT_PLANE
}

// An angle as a uv coordinate in [0, 1]; atan(0, 0), undefined in GLSL, is pinned to 0.5.
SHARED_FN float angle_uv(float y, float x) {
  return x == 0.0f && y == 0.0f ? 0.5f : atan(y, x) / IMPLICIT_TWO_PI + 0.5f;
}

// A unit vector perpendicular to `axis`: +x for the y axis, so a horizontal plane's uv is (x, z).
SHARED_FN vec3 implicit_tangent(vec3 axis) {
  return normalize(cross(axis, abs(axis.y) < 0.99f ? vec3(0.0f, 1.0f, 0.0f) : vec3(0.0f, 0.0f, 1.0f)));
}

// Thesis Algorithm 3.2: a sphere's uv from its normal.
SHARED_FN vec2 spherical_uv(vec3 n) {
  return vec2(angle_uv(n.x, n.z), n.y * 0.5f + 0.5f);
}

// uv at point q (near the surface), in [0, 1] but for the plane: spheres and ellipsoids their
// spherical angles; boxes the planar coordinates of the face q lies on; capsules the angle about
// their axis and the height along it (caps included); tori their two angles; planes their
// in-plane coordinates, in object units (like the floor's world x, z).
SHARED_FN vec2 implicit_primitive_uv(uint kind, vec4 a, vec4 b, vec3 q) {
  if (kind == IMPLICIT_SPHERE) return spherical_uv(length(q) > 0.0f ? normalize(q) : vec3(0.0f));
  if (kind == IMPLICIT_ELLIPSOID) {
    vec3 s = q / vec3(a);
    return spherical_uv(length(s) > 0.0f ? normalize(s) : vec3(0.0f));
  }
  if (kind == IMPLICIT_BOX) {
    vec3 s = abs(q) / vec3(a);
    vec3 f = q / (2.0f * vec3(a)) + 0.5f;
    if (s.x >= s.y && s.x >= s.z) return vec2(f.z, f.y);
    return s.y >= s.z ? vec2(f.x, f.z) : vec2(f.x, f.y);
  }
  if (kind == IMPLICIT_CAPSULE) {
    vec3 ba = vec3(b) - vec3(a);
    float len = length(ba);
    vec3 axis = len > 0.0f ? ba / len : vec3(0.0f, 1.0f, 0.0f);
    vec3 e1 = implicit_tangent(axis);
    vec3 w = q - vec3(a);
    return vec2(angle_uv(dot(w, cross(e1, axis)), dot(w, e1)), (dot(w, axis) + a.w) / (len + 2.0f * a.w));
  }
  if (kind == IMPLICIT_TORUS) return vec2(angle_uv(q.x, q.z), angle_uv(q.y, length(vec2(q.x, q.z)) - a.x));
  vec3 e1 = implicit_tangent(vec3(a));  // IMPLICIT_PLANE
  return vec2(dot(q, e1), dot(q, cross(e1, vec3(a))));
}

// Object-space point q in the node's primitive frame.
SHARED_FN vec3 implicit_to_local(GpuImplicitNode n, vec3 q) {
  return vec3(dot(vec3(n.to_local0), q) + n.to_local0.w, dot(vec3(n.to_local1), q) + n.to_local1.w,
              dot(vec3(n.to_local2), q) + n.to_local2.w);
}

#endif
