#version 450
#extension GL_GOOGLE_include_directive : require
// Texel buffers are textureBuffer (no sampler): SPIR-V 1.6 forbids a sampled image of Dim Buffer.
#extension GL_EXT_samplerless_texture_functions : require
// The thesis' "traditional" ray tracer (chapter 6, table 6.3): for every instance a slab test
// against its world AABB, then Möller–Trumbore against every triangle of its mesh.

#include "frame_bindings.glsl"
#include "triangle_tables.glsl"

// Slab test: does the ray enter the box before tmax?
bool hits_box(vec3 origin, vec3 inv_dir, vec3 box_min, vec3 box_max, float tmax) {
  COUNT(COUNTER_AABB_TESTS, 1u);
  vec3 t0 = (box_min - origin) * inv_dir;
  vec3 t1 = (box_max - origin) * inv_dir;
  vec3 lo = min(t0, t1);
  vec3 hi = max(t0, t1);
  float enter = max(max(lo.x, lo.y), max(lo.z, 0.0f));
  float leave = min(min(hi.x, hi.y), min(hi.z, tmax));
  return enter <= leave;
}

bool closest_hit(Ray ray, float tmax, out Hit hit) {
  vec3 inv_dir = safe_inverse(ray.dir);
  float best_t = tmax;
  uint best_instance = NO_INSTANCE;
  uint best_prim = 0u;
  vec2 best_uv = vec2(0.0f);
  uint count = uint(instances.length());
  for (uint i = 0u; i < count; ++i) {
    if (!hits_box(ray.origin, inv_dir, vec3(instances[i].bounds_min), vec3(instances[i].bounds_max), best_t)) continue;
    vec3 o = vec3(instances[i].world_to_object * vec4(ray.origin, 1.0f));
    vec3 d = vec3(instances[i].world_to_object * vec4(ray.dir, 0.0f));
    int first = int(instances[i].info.x);
    uint triangles = instances[i].info.y;
    for (uint k = 0u; k < triangles; ++k) {
      float t;
      vec2 uv;
      if (hits_triangle(o, d, 3 * (first + int(k)), best_t, t, uv)) {
        best_t = t;
        best_instance = i;
        best_prim = k;
        best_uv = uv;
      }
    }
  }
  if (best_instance == NO_INSTANCE) return false;
  fill_triangle_hit(best_instance, best_prim, best_uv, best_t, hit);
  return true;
}

float mesh_hit_tolerance() { return 0.0f; }  // ray-triangle hits lie on the triangle

bool any_hit(Ray ray, float tmax) {
  vec3 inv_dir = safe_inverse(ray.dir);
  uint count = uint(instances.length());
  for (uint i = 0u; i < count; ++i) {
    if (!hits_box(ray.origin, inv_dir, vec3(instances[i].bounds_min), vec3(instances[i].bounds_max), tmax)) continue;
    vec3 o = vec3(instances[i].world_to_object * vec4(ray.origin, 1.0f));
    vec3 d = vec3(instances[i].world_to_object * vec4(ray.dir, 0.0f));
    int first = int(instances[i].info.x);
    uint triangles = instances[i].info.y;
    for (uint k = 0u; k < triangles; ++k) {
      float t;
      vec2 uv;
      if (hits_triangle(o, d, 3 * (first + int(k)), tmax, t, uv)) return true;
    }
  }
  return false;
}

#include "render_main.glsl"
