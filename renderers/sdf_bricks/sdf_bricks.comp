#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
// sdf-bricks (issue 28): the thesis' scene hash and octree lists, exactly as sdf-octree reads them,
// but a mesh's distance comes from its sampled brick field (renderers/sdf_bricks/brick_field.h) instead of
// its exact per-cell triangle lists. Two ways to use the lists:
//  - per instance (default, as Unreal Engine 5 traces mesh distance fields): the ray walks the
//    leaves it crosses; in each, every listed instance whose box the ray's segment meets is
//    sphere-traced through its own field, in its own frame, over that segment only, with the
//    segment's end clamped to the best hit so far;
//  - BRICK_TRACE_MIN (--brick-trace min, the thesis' way): sphere tracing with the minimum over the
//    leaf's instances at every step.
// Hits: the field's bound is a true lower bound (brick_sample.glsl), so wherever it falls below
// BRICK_NEAR_VOXELS the next BRICK_WINDOW_VOXELS of the ray are tested against the triangles the
// exact mesh grid lists there (exact_crossing): the hit is the ray's crossing with the mesh, as
// Embree's. BRICK_HIT_FIELD (--hit field): the field's own zero crossing (UE5: below a quarter
// voxel), refined by secant steps, its normal the field's gradient; no triangle.

#include "frame_bindings.glsl"
#include "sdf_scene_distance.glsl"
#define TRAVERSAL_OVERFLOW sdf_cut
#include "ray_box.glsl"
#include "ray_triangle.glsl"
#include "sdf_exact_crossing.glsl"

#include "brick_field_bindings.glsl"
#include "brick_trace.glsl"

// The most leaves one ray walks (a bound on the loop; a pixel past it is reported cut short).
#define BRICK_MAX_LEAVES 65536u

InstanceRay instance_ray(uint instance, Ray ray) {
  int record = int(instance) * SDF_INSTANCE_TEXELS;
  InstanceRay r;
  r.o = transform_point(record + 2, ray.origin);
  r.d = transform_direction(record + 2, ray.dir);
  r.scale = uintBitsToFloat(SDF_FETCH(instance_records, record + 1).w);
  r.mesh = SDF_FETCH(instance_records, record).w;
  r.f = brick_field_info(r.mesh);
  return r;
}

// The field's gradient at object point q, in world space: normals go by the transpose of
// world_to_object (its rows at record + 2).
vec3 world_gradient(InstanceRay r, int record, vec3 q) {
  vec3 g = field_gradient(r, q);
  vec3 n = g.x * uintBitsToFloat(SDF_FETCH(instance_records, record + 2).xyz) +
           g.y * uintBitsToFloat(SDF_FETCH(instance_records, record + 3).xyz) +
           g.z * uintBitsToFloat(SDF_FETCH(instance_records, record + 4).xyz);
  return length(n) > 0.0f ? normalize(n) : -normalize(vec3(1.0f));
}

#ifndef BRICK_TRACE_MIN
// One instance over the ray's [t_lo, t_hi] (world t): sphere tracing by the field's bound; near
// the surface the exact window test (or, BRICK_HIT_FIELD, the field's own crossing). Out of steps,
// the rest of the segment goes to the exact test at once, so no surface is skipped.
bool trace_instance(Ray ray, uint instance, float t_lo, float t_hi, inout BrickHit best) {
  InstanceRay r = instance_ray(instance, ray);
  float t = t_lo, t_end = t_hi;
  clip_to_box(r.o, r.d, r.f.origin, brick_lattice_max(r.f), t, t_end);
  float voxel = r.f.voxel * r.scale;
#ifdef BRICK_HIT_FIELD
  float t_previous = t, v_previous = SDF_FAR;
  for (; t <= t_end && ray_steps < sdf.hash_dims.w; ++ray_steps) {
    COUNT(COUNTER_STEPS, 1u);
    float v = sample_at(r, t).value * r.scale;
    if (v < BRICK_FIELD_HIT_VOXELS * voxel) {
      float th = v_previous == SDF_FAR ? t : refine_field_hit(r, t_previous, v_previous, t, v);
      if (th >= best.t) return false;
      best = BrickHit(th, instance, SDF_NONE, vec2(0.0f));
      field_normal = world_gradient(r, int(instance) * SDF_INSTANCE_TEXELS, r.o + th * r.d);
      return true;
    }
    t_previous = t;
    v_previous = v;
    t += v;
  }
  if (t <= t_end) COUNT(COUNTER_OUT_OF_STEPS, 1u);
  return false;
#else
  float near = BRICK_NEAR_VOXELS * voxel, window = BRICK_WINDOW_VOXELS * voxel;
  while (t <= t_end) {
    float bound = 0.0f;
    if (ray_steps < sdf.hash_dims.w) {
      ++ray_steps;
      COUNT(COUNTER_STEPS, 1u);
      bound = sample_at(r, t).bound * r.scale;
      if (bound >= near) {
        t += bound;
        continue;
      }
    } else {
      COUNT(COUNTER_OUT_OF_STEPS, 1u);
      window = t_end - t;  // out of steps: the rest in one exact test
    }
    float t_window = min(t + max(window, bound), t_end);
    float th;
    uint triangle;
    vec2 uv;
    if (exact_crossing_in_mesh(r.o, r.d, r.mesh, max(t - BRICK_BEHIND_VOXELS * voxel, t_lo), t_window, th, triangle, uv)) {
      if (th >= best.t) return false;
      best = BrickHit(th, instance, triangle, uv);
      return true;
    }
    if (t_window >= t_end) break;
    t = t_window;
  }
  return false;
#endif
}

// The leaves the ray crosses, from the hash box's near side on; the segment of each goes to its
// listed instances whose world boxes it meets, ending at the best hit so far.
bool trace_bricks(Ray ray, float tmax, out BrickHit best) {
  best = BrickHit(tmax, SDF_NONE, SDF_NONE, vec2(0.0f));
  float t, t1;
  if (!clip_to_hash_box(ray, tmax, t, t1)) return false;
  vec3 lo = sdf.hash_origin.xyz;
  vec3 hi = lo + vec3(sdf.hash_dims.xyz) * sdf.hash_origin.w;
  ray_steps = 0u;
  bool found = false;
  for (uint leaves = 0u;; ++leaves) {
    if (leaves == BRICK_MAX_LEAVES) {
      sdf_cut = true;
      return false;
    }
    float probe = t + face_slack(ray, t);
    vec3 leaf_lo, leaf_hi;
    uint word = find_leaf(clamp(ray.origin + probe * ray.dir, lo, hi), leaf_lo, leaf_hi);
    if (sdf_cut) return false;
    float t_in = t, t_exit = t1;
    clip_to_box(ray.origin, ray.dir, leaf_lo, leaf_hi, t_in, t_exit);
    t_exit = min(max(t_exit, probe), t1);
    // Only the listed instances whose boxes meet the leaf's (listed first) can be hit inside it.
    int list = int(word & ~SDF_LEAF_BIT);
    uint count = SDF_FETCH(instance_lists, list + 1).x;
    for (uint k = 0u; k < count; ++k) {
      uint i = SDF_FETCH(instance_lists, list + 2 + int(k)).x;
      int record = int(i) * SDF_INSTANCE_TEXELS;
      float s0 = t, s1 = min(t_exit + face_slack(ray, t_exit), best.t);
      COUNT(COUNTER_AABB_TESTS, 1u);
      clip_to_box(ray.origin, ray.dir, uintBitsToFloat(SDF_FETCH(instance_records, record).xyz),
                  uintBitsToFloat(SDF_FETCH(instance_records, record + 1).xyz), s0, s1);
      if (s0 > s1) continue;
      COUNT(COUNTER_INSTANCE_EVALS, 1u);
      found = trace_instance(ray, i, s0, s1, best) || found;
    }
    if (found || t_exit >= t1) break;
    // Beyond the leaf's exit point q, the next surface is at least as far as the nearest box of
    // the instances the leaf lists (every instance that can be the closest one to a point of the
    // leaf, q included; each surface lies in its box): the walk goes on from there, past the
    // empty leaves in between.
    vec3 q = ray.origin + t_exit * ray.dir;
    float clear = SDF_FAR;
    uint listed = SDF_FETCH(instance_lists, list).x;
    for (uint k = 0u; k < listed && clear > 0.0f; ++k) {
      int record = int(SDF_FETCH(instance_lists, list + 2 + int(k)).x) * SDF_INSTANCE_TEXELS;
      COUNT(COUNTER_AABB_TESTS, 1u);
      clear = min(clear, box_distance(q, uintBitsToFloat(SDF_FETCH(instance_records, record).xyz),
                                      uintBitsToFloat(SDF_FETCH(instance_records, record + 1).xyz)));
    }
    t = t_exit + clear;
    if (t > t1) break;
  }
  return found;
}

#else  // BRICK_TRACE_MIN

struct ScenePoint {
  float bound;     // world units: the least bound over the leaf's instances
  float value;     // --hit field: the least field value
  uint instance;   // whose
  float voxel;     // its voxel in world units
  vec3 leaf_lo, leaf_hi;
  uint word;
};

ScenePoint scene_point(Ray ray, float t) {
  vec3 lo = sdf.hash_origin.xyz;
  vec3 hi = lo + vec3(sdf.hash_dims.xyz) * sdf.hash_origin.w;
  vec3 p = clamp(ray.origin + t * ray.dir, lo, hi);
  ScenePoint s;
  s.word = find_leaf(p, s.leaf_lo, s.leaf_hi);
  s.bound = SDF_FAR;
  s.value = SDF_FAR;
  s.instance = SDF_NONE;
  s.voxel = 0.0f;
  int list = int(s.word & ~SDF_LEAF_BIT);
  uint count = sdf_cut ? 0u : SDF_FETCH(instance_lists, list).x;
  for (uint k = 0u; k < count; ++k) {
    uint i = SDF_FETCH(instance_lists, list + 2 + int(k)).x;
    int record = int(i) * SDF_INSTANCE_TEXELS;
    COUNT(COUNTER_AABB_TESTS, 1u);
    uvec4 box_min = SDF_FETCH(instance_records, record);  // w: mesh
    uvec4 box_max = SDF_FETCH(instance_records, record + 1);  // w: scale
    float box = box_distance(p, uintBitsToFloat(box_min.xyz), uintBitsToFloat(box_max.xyz));
    if (box >= s.value) continue;
    COUNT(COUNTER_INSTANCE_EVALS, 1u);
    // Only the point goes into the instance's frame (not the whole ray, as instance_ray does).
    float scale = uintBitsToFloat(box_max.w);
    BrickFieldInfo field = brick_field_info(box_min.w);
    COUNT(COUNTER_FIELD_SAMPLES, 1u);
    FieldSample f = sample_field(field, transform_point(record + 2, ray.origin + t * ray.dir));
#ifdef BRICK_HIT_FIELD
    float v = f.value * scale;
#else
    float v = f.bound * scale;
#endif
    if (v < s.value) {
      s.value = v;
      s.bound = f.bound * scale;
      s.instance = i;
      s.voxel = field.voxel * scale;
    }
  }
  return s;
}

// Sphere tracing by the least bound over the leaf's instances (the thesis' step); near a surface,
// the exact window test of every listed instance whose box the window meets (the window ends at
// the leaf's side, so the leaf's list covers it).
bool trace_bricks(Ray ray, float tmax, out BrickHit best) {
  best = BrickHit(tmax, SDF_NONE, SDF_NONE, vec2(0.0f));
  float t, t1;
  if (!clip_to_hash_box(ray, tmax, t, t1)) return false;
  float t_previous = t, v_previous = SDF_FAR, t_start = t;
  uint previous_instance = SDF_NONE;
  for (uint steps = 0u; t <= t1; ++steps) {
    if (steps >= sdf.hash_dims.w) {
      // A grazing ray creeping along a surface: the rest of its segment goes to the exact test of
      // the instance nearest to its last point (as sdf-octree).
      COUNT(COUNTER_OUT_OF_STEPS, 1u);
#ifndef BRICK_HIT_FIELD
      float th;
      uint triangle;
      vec2 uv;
      if (previous_instance != SDF_NONE && exact_crossing(ray, t_previous, t1, previous_instance, th, triangle, uv)) {
        best = BrickHit(th, previous_instance, triangle, uv);
        return true;
      }
#endif
      return false;
    }
    COUNT(COUNTER_STEPS, 1u);
    ScenePoint s = scene_point(ray, t);
    if (sdf_cut) return false;
#ifdef BRICK_HIT_FIELD
    if (s.instance != SDF_NONE && s.value < BRICK_FIELD_HIT_VOXELS * s.voxel) {
      InstanceRay r = instance_ray(s.instance, ray);
      float th = previous_instance == s.instance ? refine_field_hit(r, t_previous, v_previous, t, s.value) : t;
      best = BrickHit(th, s.instance, SDF_NONE, vec2(0.0f));
      field_normal = world_gradient(r, int(s.instance) * SDF_INSTANCE_TEXELS, r.o + th * r.d);
      return th < tmax;
    }
    t_previous = t;
    v_previous = s.value;
    previous_instance = s.instance;
    t += max(s.value, face_slack(ray, t));
#else
    t_previous = t;
    previous_instance = s.instance;
    if (s.instance == SDF_NONE || s.bound >= BRICK_NEAR_VOXELS * s.voxel) {
      t += s.bound;
      continue;
    }
    float t_leaf = t, t_exit = t1;
    clip_to_box(ray.origin, ray.dir, s.leaf_lo, s.leaf_hi, t_leaf, t_exit);
    // (At least a hair: at a leaf's face, the leaf found may be the one the ray is leaving.)
    float t_window = min(t + max(BRICK_WINDOW_VOXELS * s.voxel, s.bound), max(min(t_exit, t1), t + face_slack(ray, t)));
    float t_test = t_window + face_slack(ray, t_window);
    bool found = false;
    int list = int(s.word & ~SDF_LEAF_BIT);
    uint count = SDF_FETCH(instance_lists, list + 1).x;  // those whose boxes meet the leaf's, listed first
    for (uint k = 0u; k < count; ++k) {
      uint i = SDF_FETCH(instance_lists, list + 2 + int(k)).x;
      int record = int(i) * SDF_INSTANCE_TEXELS;
      float s0 = max(t - BRICK_BEHIND_VOXELS * s.voxel, t_start), s1 = min(t_test, best.t);
      clip_to_box(ray.origin, ray.dir, uintBitsToFloat(SDF_FETCH(instance_records, record).xyz),
                  uintBitsToFloat(SDF_FETCH(instance_records, record + 1).xyz), s0, s1);
      if (s0 > s1) continue;
      float th;
      uint triangle;
      vec2 uv;
      if (exact_crossing(ray, s0, s1, i, th, triangle, uv) && th < best.t) {
        best = BrickHit(th, i, triangle, uv);
        found = true;
      }
    }
    if (found) return true;
    t = t_window;
#endif
  }
  return false;
}
#endif

#include "render_main.glsl"
