// What the sampled-field kernels share (sdf_bricks.comp: per-mesh fields; sdf_global.comp: the
// scene's one field): the ray in a field's frame, its samples, --hit field's refinement and
// gradient normal, and the hit's shading inputs (closest_hit, any_hit). Needs brick_sample.glsl
// and sdf_exact_crossing.glsl included before it; the kernel defines after it
//   bool trace_bricks(Ray ray, float tmax, out BrickHit best)
#ifndef SDFBENCH_BRICK_TRACE_GLSL
#define SDFBENCH_BRICK_TRACE_GLSL

// Near a surface (a bound below BRICK_NEAR_VOXELS) the next BRICK_WINDOW_VOXELS of the ray go to
// the exact test.
#ifndef BRICK_NEAR_VOXELS
#define BRICK_NEAR_VOXELS 1.0f
#endif
#ifndef BRICK_WINDOW_VOXELS
#define BRICK_WINDOW_VOXELS 2.0f
#endif
// A window's exact test starts this far behind its point (never before the ray's start): a step
// by a bound that is the exact distance (a flat mesh seen straight on) lands on the surface, and
// rounding may put it a hair beyond.
#define BRICK_BEHIND_VOXELS 0.05f
#define BRICK_FIELD_HIT_VOXELS 0.25f

// A rounding error of the ray's point at t (relative to its coordinates, not the scene: scales
// 0.001 and 1000 share scenes). A segment's exact test reaches this far past a region's far side
// (a leaf, a brick, the hash box), where a surface lying on that face is crossed; and a region is
// looked up this far along, so that at a face the one found is the one the ray enters.
float face_slack(Ray ray, float t) {
  vec3 p = abs(ray.origin + t * ray.dir);
  return 1e-5f * max(max(max(p.x, p.y), max(p.z, abs(t))), 1e-30f);
}

// A ray in a field's frame (t is the same parameter as the world ray's): an instance's (its mesh's
// field) or, for sdf-global, the world's (scale 1).
struct InstanceRay {
  vec3 o, d;
  float scale;  // world units per field unit
  uint mesh;
  BrickFieldInfo f;
};

FieldSample sample_at(InstanceRay r, float t) {
  COUNT(COUNTER_FIELD_SAMPLES, 1u);
  return sample_field(r.f, r.o + t * r.d);
}

// The steps of the pixel's current ray, against --max-steps (sdf.hash_dims.w).
uint ray_steps;

// --hit field: the hit's world normal.
vec3 field_normal;

// The field's gradient at field point q (central differences half a voxel apart), in the field's frame.
vec3 field_gradient(InstanceRay r, vec3 q) {
  float e = 0.5f * r.f.voxel;
  vec3 g;
  for (int axis = 0; axis < 3; ++axis) {
    vec3 step = vec3(0.0f);
    step[axis] = e;
    COUNT(COUNTER_FIELD_SAMPLES, 2u);
    g[axis] = sample_field(r.f, q + step).value - sample_field(r.f, q - step).value;
  }
  return g;
}

// --hit field: secant steps on the last bracket, from (t0, v0) (the step before, above the hit
// threshold) and (t1, v1) (below it), each kept within [t0, t1 + a voxel].
float refine_field_hit(InstanceRay r, float t0, float v0, float t1, float v1) {
  float limit = t1 + r.f.voxel * r.scale;
  for (int k = 0; k < 3 && v0 != v1; ++k) {
    float t = clamp(t1 - v1 * (t1 - t0) / (v1 - v0), t0, limit);
    float v = sample_at(r, t).value * r.scale;
    t0 = t1;
    v0 = v1;
    t1 = t;
    v1 = v;
  }
  return t1;
}

struct BrickHit {
  float t;
  uint instance;
  uint triangle;  // SDF_NONE for a field hit
  vec2 uv;
};

bool trace_bricks(Ray ray, float tmax, out BrickHit best);

// Set while any_hit traces: a kernel may then stop at some crossing before tmax instead of the nearest.
bool brick_any_hit = false;

bool closest_hit(Ray ray, float tmax, out Hit hit) {
  BrickHit b;
  if (!trace_bricks(ray, tmax, b) || b.t >= tmax) return false;
  int record = int(b.instance) * SDF_INSTANCE_TEXELS;
  uvec4 o0 = SDF_FETCH(instance_records, record + 5);
  hit.t = max(b.t, 0.0f);
  hit.instance = b.instance;
  hit.material = o0.w;
  hit.uv = b.uv;
  if (b.triangle == SDF_NONE) {
    hit.prim = NO_INSTANCE;
    hit.normal = field_normal;
    return true;
  }
  int n = int(3u * b.triangle);
  vec3 normal = interpolate_barycentric(SDF_FETCH(tri_normals, n).xyz, SDF_FETCH(tri_normals, n + 1).xyz,
                                        SDF_FETCH(tri_normals, n + 2).xyz, b.uv);
  vec3 o1 = uintBitsToFloat(SDF_FETCH(instance_records, record + 6).xyz);
  vec3 o2 = uintBitsToFloat(SDF_FETCH(instance_records, record + 7).xyz);
  uint mesh = SDF_FETCH(instance_records, record).w;
  uint first_triangle = SDF_FETCH(mesh_records, int(mesh) * SDF_MESH_TEXELS + 2).w;
  hit.prim = b.triangle - first_triangle;
  hit.normal = normalize(vec3(dot(uintBitsToFloat(o0.xyz), normal), dot(o1, normal), dot(o2, normal)));
  return true;
}

// Exact hits lie on the surface; a field hit lies within a fraction of a voxel of it, so rays
// leave it from farther out (sdf.options.y: a few of the scene's largest voxels).
float mesh_hit_tolerance() { return sdf.options.y; }

bool any_hit(Ray ray, float tmax) {
  BrickHit b;
  brick_any_hit = true;
  bool hit = trace_bricks(ray, tmax, b) && b.t < tmax;
  brick_any_hit = false;
  return hit;
}

#endif
