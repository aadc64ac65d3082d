#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
// sdf-global (issue 29): one sampled field over the whole scene (renderers/sdf_global/global_field.h), as
// Unreal Engine 5's global distance field: a step is one sample of it (the coarse level's in an
// empty brick, the brick's trilinear in a stored one), whatever the number of instances.
// Hits: the field's bound is a true lower bound on the distance to every surface (brick_sample.glsl),
// so where it falls below BRICK_NEAR_VOXELS the ray's next BRICK_WINDOW_VOXELS inside the brick are
// tested against the instances the brick lists (each through its exact mesh grid): the hit is the
// ray's crossing with the mesh, as Embree's. BRICK_HIT_FIELD (--hit field): the field's own zero
// crossing (UE5 stops below a voxel; here a quarter, refined by secant steps), its normal the
// field's gradient, its instance the listed one whose box is nearest.

#include "frame_bindings.glsl"
#include "sdf_scene_distance.glsl"
#define TRAVERSAL_OVERFLOW sdf_cut
#include "ray_box.glsl"
#include "ray_triangle.glsl"
#include "sdf_exact_crossing.glsl"
#include "brick_field_bindings.glsl"
#include "brick_trace.glsl"

// Per stored brick s: words s and s + 1 of this buffer are where its instances begin and end in it
// (sdf_global_renderer.cpp, flatten_lists).
layout(binding = 22) uniform utextureBuffer global_lists;
uint list_word(int i) { return texelFetch(global_lists, i).x; }

// The world ray in the field's frame: the field is in world units.
InstanceRay world_ray(Ray ray) {
  InstanceRay r;
  r.o = ray.origin;
  r.d = ray.dir;
  r.scale = 1.0f;
  r.mesh = 0u;
  r.f = brick_field_info(0u);
  return r;
}

// The brick holding world point p (clamped to the lattice) and the ray's exit from it.
// The same arithmetic as sample_field's, so that a sample's slot is this brick's.
uvec3 brick_at(BrickFieldInfo f, vec3 p) {
  uvec3 c = min(uvec3(max((p - f.origin) / f.voxel, vec3(0.0f))), f.bricks * BRICK_CELLS - uvec3(1u));
  return c / BRICK_CELLS;
}
float brick_exit(Ray ray, BrickFieldInfo f, uvec3 b) {
  vec3 lo = f.origin + vec3(b) * (f.voxel * float(BRICK_CELLS));
  float t0 = -3.0e38f, t1 = 3.0e38f;
  clip_to_box(ray.origin, ray.dir, lo, lo + f.voxel * float(BRICK_CELLS), t0, t1);
  return t1;
}

// Sphere tracing by the bound from t until it falls below BRICK_NEAR_VOXELS in a stored brick
// (true, that sample in s) or the segment or the steps run out (false). The exact test is kept
// out of this loop, so that the SIMD lanes of a CPU device step together and then test together
// (lavapipe: 1.6x against the test inside the stepping loop's branch).
bool march_to_near(Ray ray, InstanceRay r, inout float t, float t1, out FieldSample s) {
  for (; t <= t1 && ray_steps < sdf.hash_dims.w; ++ray_steps) {
    COUNT(COUNTER_STEPS, 1u);
    s = sample_at(r, t);
    if (s.bound < BRICK_NEAR_VOXELS * r.f.voxel && s.slot != BRICK_EMPTY) return true;
    // An empty brick holds no surface: the ray goes on from its far side at least.
    float t_next = t + s.bound;
    if (s.empty) t_next = max(t_next, brick_exit(ray, r.f, brick_at(r.f, ray.origin + t * ray.dir)));
    t = max(t_next, t + face_slack(ray, t));
  }
  return false;
}

#ifdef GLOBAL_REF_SPLIT
#include "global_cell_refs.glsl"
#endif

// The earliest exact crossing over [s0, s1] of the instances stored brick `slot` lists (every
// instance whose surface comes within kListSlackVoxels of the brick); keeps it in `best`.
// Instance i's earliest crossing with the ray over [a, b] (clipped to its box), kept in `best`
// when nearer.
bool exact_instance(Ray ray, uint i, float a, float b, inout BrickHit best) {
  int record = int(i) * SDF_INSTANCE_TEXELS;
  COUNT(COUNTER_AABB_TESTS, 1u);
  clip_to_box(ray.origin, ray.dir, uintBitsToFloat(SDF_FETCH(instance_records, record).xyz),
              uintBitsToFloat(SDF_FETCH(instance_records, record + 1).xyz), a, b);
  if (a > b) return false;
  COUNT(COUNTER_INSTANCE_EVALS, 1u);
  float th;
  uint triangle;
  vec2 uv;
  if (!exact_crossing(ray, a, b, i, th, triangle, uv) || th >= best.t) return false;
  best = BrickHit(th, i, triangle, uv);
  return true;
}

bool exact_in_brick(Ray ray, uint slot, float s0, float s1, inout BrickHit best) {
  int begin = int(list_word(int(slot))), end = int(list_word(int(slot) + 1));
  bool found = false;
  for (int k = begin; k < end; ++k) found = exact_instance(ray, list_word(k), s0, min(s1, best.t), best) || found;
  return found;
}

#ifdef GLOBAL_SPAN_RAY
// --exact-span ray: each listed instance is tested once, over the rest of the ray (up to the
// nearest crossing so far), the first time a near point's brick lists it; up to GLOBAL_TESTED_MAX
// instances are remembered. A brick whose listed instances are all remembered holds no crossing
// the ray has not found already, so it is passed whole (`whole`): the march never creeps onto a
// tested surface. Instances beyond the memory are tested over the window [s0, s1] (as
// --exact-span window), and their brick is not passed whole.
#define GLOBAL_TESTED_MAX 8
uint tested[GLOBAL_TESTED_MAX];
uint tested_count;

bool exact_listed_once(Ray ray, uint slot, float s0, float s1, inout BrickHit best, out bool whole) {
  int begin = int(list_word(int(slot))), end = int(list_word(int(slot) + 1));
  bool found = false;
  whole = true;
  for (int k = begin; k < end; ++k) {
    uint i = list_word(k);
    bool seen = false;
    for (uint j = 0u; j < tested_count; ++j) seen = seen || tested[j] == i;
    if (seen) continue;
    float b = best.t;
    if (tested_count < GLOBAL_TESTED_MAX) {
      tested[tested_count++] = i;
    } else {
      whole = false;
      b = min(s1, best.t);
    }
    found = exact_instance(ray, i, s0, b, best) || found;
  }
  return found;
}
#endif

#ifdef BRICK_HIT_FIELD
// The listed instance of stored brick `slot` whose box is nearest to p (the field does not say
// whose surface it is; UE5 keeps a per-page object grid for this).
uint nearest_listed(uint slot, vec3 p) {
  int begin = int(list_word(int(slot))), end = int(list_word(int(slot) + 1));
  uint nearest = SDF_NONE;
  float best = SDF_FAR;
  for (int k = begin; k < end; ++k) {
    uint i = list_word(k);
    int record = int(i) * SDF_INSTANCE_TEXELS;
    COUNT(COUNTER_AABB_TESTS, 1u);
    float d = box_distance(p, uintBitsToFloat(SDF_FETCH(instance_records, record).xyz),
                           uintBitsToFloat(SDF_FETCH(instance_records, record + 1).xyz));
    if (d < best) {
      best = d;
      nearest = i;
    }
  }
  return nearest;
}
#else
// Out of steps (a grazing ray creeping along a surface): the rest of the segment brick by brick,
// each stored brick's listed instances tested exactly over the ray's part inside it; empty bricks
// hold no surface.
bool walk_bricks(Ray ray, BrickFieldInfo f, float t, float t1, float t_start, inout BrickHit best) {
  uint limit = 3u * (f.bricks.x + f.bricks.y + f.bricks.z) + 16u;
  for (uint n = 0u; n < limit; ++n) {
    if (t > t1) return false;
    float probe = t + face_slack(ray, t);
    uvec3 b = brick_at(f, ray.origin + probe * ray.dir);
    float t_exit = max(min(brick_exit(ray, f, b), t1), probe);
    uint slot = brick_slot(int(f.first_brick + b.x + f.bricks.x * (b.y + f.bricks.y * b.z)));
    if (slot != BRICK_EMPTY &&
        exact_in_brick(ray, slot, max(t - BRICK_BEHIND_VOXELS * f.voxel, t_start), t_exit + face_slack(ray, t_exit), best))
      return true;
    t = t_exit;
  }
  if (t <= t1) sdf_cut = true;
  return false;
}
#endif

bool trace_bricks(Ray ray, float tmax, out BrickHit best) {
  best = BrickHit(tmax, SDF_NONE, SDF_NONE, vec2(0.0f));
  InstanceRay r = world_ray(ray);
  float t = 0.0f, t1 = tmax;
  clip_to_box(ray.origin, ray.dir, r.f.origin, brick_lattice_max(r.f), t, t1);
  float t_start = t, voxel = r.f.voxel;
#ifdef BRICK_HIT_FIELD
  float t_previous = t, v_previous = SDF_FAR;
  for (ray_steps = 0u; t <= t1; ++ray_steps) {
    if (ray_steps >= sdf.hash_dims.w) {
      COUNT(COUNTER_OUT_OF_STEPS, 1u);
      return false;
    }
    COUNT(COUNTER_STEPS, 1u);
    FieldSample s = sample_at(r, t);
    float v = s.value;
    if (v < BRICK_FIELD_HIT_VOXELS * voxel && s.slot != BRICK_EMPTY) {
      float th = v_previous == SDF_FAR ? t : refine_field_hit(r, t_previous, v_previous, t, v);
      vec3 q = ray.origin + th * ray.dir;
      uint instance = nearest_listed(s.slot, q);
      if (instance != SDF_NONE) {
        best = BrickHit(th, instance, SDF_NONE, vec2(0.0f));
        vec3 g = field_gradient(r, q);
        field_normal = length(g) > 0.0f ? normalize(g) : -ray.dir;
        return th < tmax;
      }
    }
    t_previous = t;
    v_previous = v;
    t += max(v, face_slack(ray, t));
  }
  return false;
#elif defined(GLOBAL_REF_SPLIT)
  return trace_cells(ray, r, t, t1, t_start, best);
#elif defined(GLOBAL_SPAN_RAY)
  ray_steps = 0u;
  tested_count = 0u;
  bool found = false;
  // Past the nearest crossing found so far nothing can be nearer: the segment shrinks to it.
  while (t <= min(t1, best.t)) {
    float t_end = min(t1, best.t);
    FieldSample s;
    if (!march_to_near(ray, r, t, t_end, s)) {
      if (t <= t_end) {
        COUNT(COUNTER_OUT_OF_STEPS, 1u);
        return walk_bricks(ray, r.f, t, t_end, t_start, best) || found;
      }
      return found;
    }
    ++ray_steps;
    float t_exit = brick_exit(ray, r.f, brick_at(r.f, ray.origin + t * ray.dir));
    float t_window = max(min(min(t + max(BRICK_WINDOW_VOXELS * voxel, s.bound), t_exit), t_end), t + face_slack(ray, t));
    bool whole;
    if (exact_listed_once(ray, s.slot, max(t - BRICK_BEHIND_VOXELS * voxel, t_start), t_window + face_slack(ray, t_window),
                          best, whole)) {
      found = true;
      if (brick_any_hit) return true;  // a shadow ray needs some crossing, not the nearest
    }
    t = whole ? max(t_exit, t + face_slack(ray, t)) : t_window;
  }
  return found;
#else
  ray_steps = 0u;
  while (t <= t1) {
    FieldSample s;
    if (!march_to_near(ray, r, t, t1, s)) {
      if (t <= t1) {
        COUNT(COUNTER_OUT_OF_STEPS, 1u);
        return walk_bricks(ray, r.f, t, t1, t_start, best);
      }
      return false;
    }
    ++ray_steps;
    // The window ends inside the brick (its list covers only the brick), and moves at least a hair
    // (at a brick's face the brick found may be the one the ray leaves).
    float t_exit = brick_exit(ray, r.f, brick_at(r.f, ray.origin + t * ray.dir));
    float t_window = max(min(min(t + max(BRICK_WINDOW_VOXELS * voxel, s.bound), t_exit), t1), t + face_slack(ray, t));
    if (exact_in_brick(ray, s.slot, max(t - BRICK_BEHIND_VOXELS * voxel, t_start), t_window + face_slack(ray, t_window), best))
      return true;
    t = t_window;
  }
  return false;
#endif
}

#include "render_main.glsl"
