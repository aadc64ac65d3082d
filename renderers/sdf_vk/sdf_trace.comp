#version 450
#extension GL_GOOGLE_include_directive : require
// Texel buffers are textureBuffer (no sampler): SPIR-V 1.6 forbids a sampled image of Dim Buffer.
#extension GL_EXT_samplerless_texture_functions : require
// The thesis' renderer (chapters 4-5): sphere tracing (Hart 1996) through the scene hash and
// its octrees, for both sdf-hash (octree depth 0: a leaf per cell) and sdf-octree. The same
// algorithm as SphereTracer in renderers/sdf/sphere_tracer.cpp, so the images and the work
// counters agree with sdf-cpu.

#include "frame_bindings.glsl"
#include "sdf_scene_distance.glsl"

// March inside the hash box (outside it there is nothing to hit) up to tmax; returns the hit's
// t, or -1 after max steps or past the box.
float march(Ray ray, float tmax, out SceneDistance at_hit) {
  vec3 lo = sdf.hash_origin.xyz;
  vec3 hi = lo + vec3(sdf.hash_dims.xyz) * sdf.hash_origin.w;
  float t0 = 0.0f, t1 = tmax;
  for (int axis = 0; axis < 3; ++axis) {
    float inv = 1.0f / ray.dir[axis];
    float a = (lo[axis] - ray.origin[axis]) * inv, b = (hi[axis] - ray.origin[axis]) * inv;
    if (a > b) {
      float s = a;
      a = b;
      b = s;
    }
    t0 = t0 < a ? a : t0;  // std::max / std::min: a NaN slab (ray in the plane) changes nothing
    t1 = b < t1 ? b : t1;
  }
  if (t0 > t1) return -1.0f;
  float t = t0;
  for (uint step = 0u; step < sdf.hash_dims.w && t <= t1; ++step) {
    COUNT(COUNTER_STEPS, 1u);
    // Clamped: the clip's rounding can leave a point a hair outside the box, where a step would
    // be wasted (and wasted differently by sdf-cpu, so the counters would not agree).
    SceneDistance d = scene_distance(clamp(ray.origin + t * ray.dir, lo, hi));
    // A hit needs an exact distance (a listed triangle), not a bound from outside a grid box.
    if (d.distance < sdf.tracing.x && d.triangle != SDF_NONE) {
      at_hit = d;
      return t;
    }
    // At least epsilon: where the ray enters the box, rounding can leave the point a hair
    // outside it, and a bound of ~1e-7 would not move t at all (the ray then stalls to a miss).
    t += max(d.distance, sdf.tracing.x);
  }
  return -1.0f;
}

// The surface normal and uv come from the closest triangle (stored, as in the thesis), not
// from the field's gradient.
bool closest_hit(Ray ray, float tmax, out Hit hit) {
  SceneDistance d;
  float t = march(ray, tmax, d);
  if (t < 0.0f) return false;
  int record = int(d.instance) * SDF_INSTANCE_TEXELS;
  vec3 p = transform_point(record + 2, ray.origin + t * ray.dir);
  vec3 a = fetch_triangle_vertex(d.triangle, 0), b = fetch_triangle_vertex(d.triangle, 1),
       c = fetch_triangle_vertex(d.triangle, 2);
  vec2 uv = barycentric(closest_on_triangle(p, a, b, c), a, b, c);
  int n = int(3u * d.triangle);
  vec3 normal = interpolate_barycentric(texelFetch(tri_normals, n).xyz, texelFetch(tri_normals, n + 1).xyz,
                                        texelFetch(tri_normals, n + 2).xyz, uv);
  uvec4 o0 = texelFetch(instance_records, record + 5);
  vec3 o1 = uintBitsToFloat(texelFetch(instance_records, record + 6).xyz);
  vec3 o2 = uintBitsToFloat(texelFetch(instance_records, record + 7).xyz);
  uint mesh = texelFetch(instance_records, record).w;
  uint first_triangle = texelFetch(mesh_records, int(mesh) * SDF_MESH_TEXELS + 2).w;
  hit.t = t;
  hit.instance = d.instance;
  hit.prim = d.triangle - first_triangle;
  hit.material = o0.w;
  hit.normal = normalize(vec3(dot(uintBitsToFloat(o0.xyz), normal), dot(o1, normal), dot(o2, normal)));
  hit.uv = uv;
  return true;
}

// Shadow rays: the first hit is enough.
bool any_hit(Ray ray, float tmax) {
  SceneDistance d;
  return march(ray, tmax, d) >= 0.0f;
}

#include "render_main.glsl"
