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
#define TRAVERSAL_OVERFLOW sdf_cut
#include "ray_box.glsl"
#include "ray_triangle.glsl"
#include "sdf_exact_crossing.glsl"

// Per ray (trace_sdf): --hit exact's footprint fraction x the angle of one pixel.
float sdf_cone;

// The hit threshold at t. --hit thesis: hit_epsilon x the scene scale. --hit exact: a fraction of
// the pixel's footprint at t (a cone of the pixel's angle, as in cone tracing), so that it
// follows the ray, not the scene, never below float precision at the point. As sdf-cpu.
float hit_epsilon(Ray ray, float t) {
  if (sdf.tracing.y < 0.5f) return sdf.tracing.x;
  vec3 p = abs(ray.origin + t * ray.dir);
  return max(sdf_cone * t, 1e-6f * max(max(p.x, p.y), max(p.z, t)));
}

const uint MARCH_CONVERGED = 0u;  // closer than epsilon to a listed triangle at t
const uint MARCH_LEFT = 1u;       // past t1: nothing there
const uint MARCH_OUT_OF_STEPS = 2u;

// Sphere tracing from t towards t1, `steps` of the ray's budget already spent; `last` is the
// distance at `t_last`, the last point queried (at a convergence: t), `last_leaf` that point's
// leaf word. The end test allows one epsilon past t1: a step that lands a rounding error beyond
// the box's far face (a wall lying on it) would otherwise end the march in front of the surface.
// --over-relax's fallback: back to the previous point's plain step, plain steps from then on.
void step_back(inout float t, inout float omega, inout float step, float t_previous, float plain_previous) {
  t = t_previous + plain_previous;
  omega = 1.0f;
  step = 0.0f;
}

// --over-relax (Keinert et al. 2014), as SphereTracer::march: steps of omega x the distance while
// the spheres at both ends of a step overlap; else back to the previous point's plain step, and
// plain steps from then on.
uint march(Ray ray, float t1, inout float t, inout uint steps, inout SceneDistance last, inout float t_last,
           inout uint last_leaf) {
  vec3 lo = sdf.hash_origin.xyz;
  vec3 hi = lo + vec3(sdf.hash_dims.xyz) * sdf.hash_origin.w;
  float omega = sdf.options.x, t_previous = t, plain_previous = 0.0f, previous = 0.0f, step = 0.0f;
  for (; steps < sdf.hash_dims.w; ++steps) {
    float epsilon = hit_epsilon(ray, t);
    if (t > t1 + epsilon) {
      // A relaxed step past the box's far side is unchecked: it may have jumped a surface there.
      if (step > plain_previous) {
        step_back(t, omega, step, t_previous, plain_previous);
        continue;
      }
      return MARCH_LEFT;
    }
    COUNT(COUNTER_STEPS, 1u);
    // Clamped: the clip's rounding can leave a point a hair outside the box, where a step would
    // be wasted (and wasted differently by sdf-cpu, so the counters would not agree).
    vec3 p = clamp(ray.origin + t * ray.dir, lo, hi);
    vec3 leaf_lo, leaf_hi;
    uint word = find_leaf(p, leaf_lo, leaf_hi);
    if (sdf_cut) return MARCH_LEFT;  // the pixel is reported cut short
#ifdef SDF_CELL_BOUND
    // No surface lies within `bound` of the leaf: the ray crosses it and goes the bound beyond its
    // far side (still that far from any surface) without evaluating an instance.
    float bound = leaf_bound(word);
    if (bound > 0.0f) {
      // The bound is also this point's distance for the over-relaxation check of the step here.
      if (omega > 1.0f && bound + previous < step) {
        step_back(t, omega, step, t_previous, plain_previous);
        continue;
      }
      float t_in = t, t_out = 3.0e38f;
      clip_to_box(ray.origin, ray.dir, leaf_lo, leaf_hi, t_in, t_out);
      t = max(t, t_out) + bound;
      t_previous = t;
      plain_previous = previous = step = 0.0f;
      continue;
    }
#endif
    SceneDistance d = leaf_distance(p, word);
    last = d;
    t_last = t;
    last_leaf = word;
    if (omega > 1.0f && d.distance + previous < step) {
      step_back(t, omega, step, t_previous, plain_previous);
      continue;
    }
    // A hit needs an exact distance (a listed triangle), not a bound from outside a grid box or
    // from a far cell.
    if (d.distance < epsilon && d.triangle < SDF_FAR_TRIANGLE) {
      ++steps;
      return MARCH_CONVERGED;
    }
    // At least epsilon: where the ray enters the box, rounding can leave the point a hair
    // outside it, and a bound of ~1e-7 would not move t at all (the ray then stalls to a miss).
    // A far cell's bound is stepped as it is (SDF_FAR_TRIANGLE).
    float least = d.triangle == SDF_FAR_TRIANGLE ? 0.0f : epsilon;
    float plain = max(d.distance, least);
    step = omega > 1.0f ? max(omega * d.distance, least) : plain;
    t_previous = t;
    plain_previous = plain;
    previous = d.distance;
    t += step;
  }
  return t > t1 + hit_epsilon(ray, t) ? MARCH_LEFT : MARCH_OUT_OF_STEPS;
}

// The earliest exact crossing in [t - epsilon, t + epsilon] around a converged point: of the
// instance nearest to it, and of every other instance its leaf (`word`) lists whose box meets that
// window. Where instances overlap, another one's surface can cross the window before the nearest
// one's. As SphereTracer::window_crossing.
bool window_crossing(Ray ray, float t, float epsilon, uint nearest, uint word, out float t_hit, out uint instance,
                     out uint triangle, out vec2 uv) {
  bool found = exact_crossing(ray, t - epsilon, t + epsilon, nearest, t_hit, triangle, uv);
  instance = nearest;
  // The leaf lists every instance that can be closest at t; the others' surfaces in the window lie
  // in their boxes, and only before the best crossing so far can they win.
  int list = int(word & ~SDF_LEAF_BIT);
  uint count = SDF_FETCH(instance_lists, list).x;
  for (uint k = 0u; k < count; ++k) {
    uint i = SDF_FETCH(instance_lists, list + 2 + int(k)).x;
    if (i == nearest) continue;
    COUNT(COUNTER_AABB_TESTS, 1u);
    int record = int(i) * SDF_INSTANCE_TEXELS;
    float s0 = t - epsilon, s1 = found ? t_hit : t + epsilon;
    clip_to_box(ray.origin, ray.dir, uintBitsToFloat(SDF_FETCH(instance_records, record).xyz),
                uintBitsToFloat(SDF_FETCH(instance_records, record + 1).xyz), s0, s1);
    float ti;
    uint tri;
    vec2 uvi;
    if (s0 > s1 || !exact_crossing(ray, s0, s1, i, ti, tri, uvi)) continue;
    // Ties go to the lower instance index, as in sdf-cpu.
    if (!found || ti < t_hit || (ti == t_hit && i < instance)) {
      t_hit = ti;
      instance = i;
      triangle = tri;
      uv = uvi;
      found = true;
    }
  }
  return found;
}

// The first surface along the ray before tmax. --hit thesis: the first converged point, its
// normal and uv from the closest point on the nearest triangle (as in the thesis). --hit exact:
// a converged point where the ray crosses no listed triangle passed the surface within epsilon
// (a silhouette), and the march goes on; a ray that runs out of steps tests the rest of its
// segment against the instance nearest to its last point, and only then falls back to its first
// converged point. The search (window_crossing) covers one epsilon on either side of the
// converged point, as far as a step can go, for every instance whose surface can lie there, so
// converging again near the same instance before that segment's end needs no second test.
bool trace_sdf(Ray ray, float tmax, out float t, out uint instance, out uint triangle, out vec2 uv) {
  float t1;
  if (!clip_to_hash_box(ray, tmax, t, t1)) return false;
  uint steps = 0u;
  bool exact = sdf.tracing.y > 0.5f;
  sdf_cone = sdf.tracing.z * 2.0f * length(vec3(frame.camera_up)) / float(frame.image.y);
  bool converged_before = false;
  float first_t = 0.0f;
  SceneDistance first;
  uint cleared_instance = SDF_NONE;
  float cleared_until = 0.0f;
  SceneDistance d = SceneDistance(0.0f, SDF_NONE, SDF_NONE);
  float t_last = t;
  uint leaf = SDF_LEAF_BIT;
  uint end;
  while ((end = march(ray, t1, t, steps, d, t_last, leaf)) == MARCH_CONVERGED) {
    float epsilon = hit_epsilon(ray, t);
    if (exact && (d.instance != cleared_instance || t > cleared_until)) {
      float t_hit;
      bool crossed = window_crossing(ray, t, epsilon, d.instance, leaf, t_hit, instance, triangle, uv);
      // (SDF_REPEAT_EXACT: the time breakdown's copy, as in sdf_scene_distance.glsl.)
      for (int r = 1; r < SDF_REPEAT_EXACT; ++r)
        crossed = window_crossing(ray, t + float(r) * sdf.tracing.w, epsilon, d.instance, leaf, t_hit, instance, triangle, uv);
      if (crossed) {
        if (t_hit >= tmax) return false;
        t = max(t_hit, 0.0f);
        return true;
      }
      cleared_instance = d.instance;
      cleared_until = t + epsilon;
    }
    if (!converged_before) {
      converged_before = true;
      first_t = t;
      first = d;
    }
    if (!exact) break;
    t += epsilon;  // the converged distance is below it
  }
  if (end == MARCH_OUT_OF_STEPS) {
    COUNT(COUNTER_OUT_OF_STEPS, 1u);
    // A grazing ray creeping along a surface: the rest of its segment goes to the exact test of
    // the instance nearest to its last point (no surface was crossed before it).
    float t_hit;
    if (exact && d.instance != SDF_NONE &&
        exact_crossing(ray, t_last - hit_epsilon(ray, t_last), t1, d.instance, t_hit, triangle, uv)) {
      if (t_hit >= tmax) return false;
      t = max(t_hit, 0.0f);
      instance = d.instance;
      return true;
    }
  }
  if (!converged_before || (exact && end != MARCH_OUT_OF_STEPS)) return false;
  t = first_t;
  instance = first.instance;
  triangle = first.triangle;
  int record = int(instance) * SDF_INSTANCE_TEXELS;
  vec3 p = transform_point(record + 2, ray.origin + t * ray.dir);
  vec3 a = fetch_triangle_vertex(triangle, 0), b = fetch_triangle_vertex(triangle, 1),
       c = fetch_triangle_vertex(triangle, 2);
  uv = barycentric(closest_on_triangle(p, a, b, c), a, b, c);
  return true;
}

// The surface normal and uv are interpolated from the triangle's vertices at uv.
bool closest_hit(Ray ray, float tmax, out Hit hit) {
  float t;
  uint instance, triangle;
  vec2 uv;
  if (!trace_sdf(ray, tmax, t, instance, triangle, uv)) return false;
  int record = int(instance) * SDF_INSTANCE_TEXELS;
  int n = int(3u * triangle);
  vec3 normal = interpolate_barycentric(SDF_FETCH(tri_normals, n).xyz, SDF_FETCH(tri_normals, n + 1).xyz,
                                        SDF_FETCH(tri_normals, n + 2).xyz, uv);
  uvec4 o0 = SDF_FETCH(instance_records, record + 5);
  vec3 o1 = uintBitsToFloat(SDF_FETCH(instance_records, record + 6).xyz);
  vec3 o2 = uintBitsToFloat(SDF_FETCH(instance_records, record + 7).xyz);
  uint mesh = SDF_FETCH(instance_records, record).w;
  uint first_triangle = SDF_FETCH(mesh_records, int(mesh) * SDF_MESH_TEXELS + 2).w;
  hit.t = t;
  hit.instance = instance;
  hit.prim = triangle - first_triangle;
  hit.material = o0.w;
  hit.normal = normalize(vec3(dot(uintBitsToFloat(o0.xyz), normal), dot(o1, normal), dot(o2, normal)));
  hit.uv = uv;
  return true;
}

// --hit exact: the ray-triangle crossing lies on the surface; --hit thesis: the converged point
// lies within epsilon of it, and a ray leaving it must start well outside (as sdf-cpu).
float mesh_hit_tolerance() {
  return sdf.tracing.y > 0.5f ? 0.0f : SDF_THESIS_OFFSET_EPSILONS * sdf.tracing.x;
}

// Shadow rays: the first surface is enough (in exact mode the first crossing, as for closest_hit).
bool any_hit(Ray ray, float tmax) {
  float t;
  uint instance, triangle;
  vec2 uv;
  return trace_sdf(ray, tmax, t, instance, triangle, uv);
}

#include "render_main.glsl"
