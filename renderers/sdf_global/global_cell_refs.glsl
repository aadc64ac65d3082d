// sdf-global's exact hits through triangle references (--exact-lists triangles;
// renderers/sdf_global/cell_triangle_refs.h): a stored brick's reference cells along the ray, each
// cell's set of (instance, triangle) pairs tested once over the ray's part in the cell. Needs
// sdf_exact_crossing.glsl, brick_trace.glsl and the kernel's brick_exit() and march_to_near()
// before it;
// GLOBAL_REF_SPLIT is --list-split.
#ifndef SDFBENCH_GLOBAL_CELL_REFS_GLSL
#define SDFBENCH_GLOBAL_CELL_REFS_GLSL

// Words 0 .. stored bricks - 1: each stored brick's cell table (its start in this buffer), or
// SDF_NONE where no triangle crosses the brick; then the tables, a set offset per cell.
layout(binding = 25) uniform utextureBuffer ref_cells;
// Sets: a count n, then n words: SDF_INSTANCE_WORD | instance (the triangles after it are its) or a
// global triangle index.
layout(binding = 26) uniform utextureBuffer ref_sets;
uint ref_cell_word(int i) { return texelFetch(ref_cells, i).x; }
uint ref_set_word(int i) { return texelFetch(ref_sets, i).x; }

#define SDF_INSTANCE_WORD 0x80000000u
#define REF_SIDE (BRICK_CELLS * uint(GLOBAL_REF_SPLIT))

// The earliest crossing in [a, b] with the triangles of the set at `offset`, each in its
// instance's frame (t is the world ray's parameter there too); kept in `best`.
bool test_ref_set(Ray ray, int offset, float a, float b, inout BrickHit best) {
  int n = int(ref_set_word(offset));
  COUNT(COUNTER_CELL_SETS, 1u);
  vec3 o = vec3(0.0f), d = vec3(0.0f);
  uint instance = SDF_NONE;
  bool found = false;
  for (int k = offset + 1; k <= offset + n; ++k) {
    uint w = ref_set_word(k);
    if ((w & SDF_INSTANCE_WORD) != 0u) {
      instance = w & ~SDF_INSTANCE_WORD;
      int record = int(instance) * SDF_INSTANCE_TEXELS;
      o = transform_point(record + 2, ray.origin);
      d = transform_direction(record + 2, ray.dir);
      COUNT(COUNTER_INSTANCE_EVALS, 1u);
      continue;
    }
    int v = 3 * int(w);
    float tk;
    vec2 uvk;
    COUNT(COUNTER_TRIANGLE_TESTS, 1u);
    if (ray_triangle(o, d, SDF_FETCH(tri_vertices, v).xyz, SDF_FETCH(tri_vertices, v + 1).xyz,
                     SDF_FETCH(tri_vertices, v + 2).xyz, tk, uvk) &&
        tk >= a && tk <= b && tk < best.t) {
      best = BrickHit(tk, instance, w, uvk);
      found = true;
    }
  }
  return found;
}

// The reference cells of stored brick `slot` (lattice brick `brick`) that the ray crosses from
// t_from on, until the cell holding t_until (or the brick's exit): each cell's set tested over the
// ray's part in it (the first from t_lo, a little behind t_from). True at the first cell with a
// crossing: the ray's hit, as every crossing inside a cell is in its set. `t_done`: where the
// walk stopped; the ray holds no crossing before it. A brick no triangle crosses is passed whole.
bool exact_in_cells(Ray ray, BrickFieldInfo f, uint slot, uvec3 brick, float t_from, float t_lo, float t_until,
                    inout BrickHit best, out float t_done) {
  float t_brick = brick_exit(ray, f, brick);
  uint table = ref_cell_word(int(slot));
  if (table == SDF_NONE) {
    t_done = max(t_brick, t_from);
    return false;
  }
  // Amanatides & Woo's walk: each step crosses the nearest of the cell's three exit planes.
  float cell = f.voxel / float(GLOBAL_REF_SPLIT);
  ivec3 first = ivec3(brick * REF_SIDE), last = first + ivec3(REF_SIDE - 1u);
  float probe = t_from + face_slack(ray, t_from);
  // Clamped to the brick: at its faces rounding can put the point a hair outside.
  ivec3 c = clamp(ivec3(floor((ray.origin + probe * ray.dir - f.origin) / cell)), first, last);
  ivec3 step = ivec3(sign(ray.dir));
  vec3 t_next, t_delta;
  for (int axis = 0; axis < 3; ++axis) {
    float inv = 1.0f / ray.dir[axis];
    float plane = f.origin[axis] + float(c[axis] + (step[axis] > 0 ? 1 : 0)) * cell;
    t_next[axis] = step[axis] == 0 ? 3.0e38f : max((plane - ray.origin[axis]) * inv, probe);
    t_delta[axis] = step[axis] == 0 ? 3.0e38f : cell * abs(inv);
  }
  float a = t_lo;
  for (uint n = 0u; n < 3u * REF_SIDE + 3u; ++n) {
    float t_exit = min(t_next.x, min(t_next.y, t_next.z));
    ivec3 l = c - first;
    uint set = ref_cell_word(int(table) + l.x + int(REF_SIDE) * (l.y + int(REF_SIDE) * l.z));
    if (set != 0u && test_ref_set(ray, int(set), a, t_exit + face_slack(ray, t_exit), best)) return true;
    a = t_exit;
    if (t_exit >= t_until || t_exit >= t_brick) break;
    int axis = t_next.x == t_exit ? 0 : (t_next.y == t_exit ? 1 : 2);
    c[axis] += step[axis];
    if (c[axis] < first[axis] || c[axis] > last[axis]) break;
    t_next[axis] += t_delta[axis];
  }
  t_done = max(a, t_from);
  return false;
}

// --hit exact with the references: sphere tracing by the field's bound; where it falls below
// BRICK_NEAR_VOXELS, the reference cells of the ray's next BRICK_WINDOW_VOXELS (or the bound's
// step) in that brick. Out of steps (a grazing ray creeping along a surface), the rest of the
// segment cell by cell. One call site of the cell walk, so that the kernel holds one copy of it.
bool trace_cells(Ray ray, InstanceRay r, float t, float t1, float t_start, inout BrickHit best) {
  float voxel = r.f.voxel;
  bool walking = false;
  uint walked = 0u, walk_limit = 3u * (r.f.bricks.x + r.f.bricks.y + r.f.bricks.z) * REF_SIDE + 16u;
  ray_steps = 0u;
  while (t <= t1) {
    float bound = 0.0f;
    uint slot = BRICK_EMPTY;
    if (!walking) {
      FieldSample s;
      if (march_to_near(ray, r, t, t1, s)) {
        bound = s.bound;
        slot = s.slot;
        ++ray_steps;
      } else {
        if (t > t1) return false;
        COUNT(COUNTER_OUT_OF_STEPS, 1u);
        walking = true;
      }
    }
    // Marching: the sampled brick (the same arithmetic as the sample's); walking: the one ahead.
    uvec3 b = brick_at(r.f, ray.origin + (walking ? t + face_slack(ray, t) : t) * ray.dir);
    if (walking) {
      if (++walked > walk_limit) {
        sdf_cut = true;
        return false;
      }
      slot = brick_slot(int(r.f.first_brick + b.x + r.f.bricks.x * (b.y + r.f.bricks.y * b.z)));
    }
    float t_done = brick_exit(ray, r.f, b);
    if (slot != BRICK_EMPTY &&
        exact_in_cells(ray, r.f, slot, b, t, max(t - BRICK_BEHIND_VOXELS * voxel, t_start),
                       walking ? t1 : t + max(BRICK_WINDOW_VOXELS * voxel, bound), best, t_done))
      return true;
    t = max(t_done, t + face_slack(ray, t));
  }
  return false;
}

#endif
