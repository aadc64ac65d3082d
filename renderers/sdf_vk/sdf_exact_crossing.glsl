// --hit exact's ray-triangle crossing search of the SDF kernels (sdf_trace.comp, sdf_bricks.comp,
// sdf_global.comp)
// and the ray's clip to the scene hash box. Needs sdf_scene_distance.glsl, ray_box.glsl and
// ray_triangle.glsl included before it.
#ifndef SDFBENCH_SDF_EXACT_CROSSING_GLSL
#define SDFBENCH_SDF_EXACT_CROSSING_GLSL

// Per mesh grid cell (indexed as grid_cells) the (begin, end) of its entries in crossing_triangles,
// each a global triangle whose box meets the cell (sdf_gpu_arrays.h).
#ifdef SDF_STORAGE_TABLES
layout(std430, binding = 23) readonly buffer CrossingCells { uvec2 crossing_cells[]; };
layout(std430, binding = 24) readonly buffer CrossingTriangles { uint crossing_triangles[]; };
#else
layout(binding = 23) uniform utextureBuffer crossing_cells;      // RG32UI
layout(binding = 24) uniform utextureBuffer crossing_triangles;  // R32UI
#endif

// The ray's segment inside the hash box (outside it there is nothing to hit), up to tmax.
bool clip_to_hash_box(Ray ray, float tmax, out float t0, out float t1) {
  vec3 lo = sdf.hash_origin.xyz;
  vec3 hi = lo + vec3(sdf.hash_dims.xyz) * sdf.hash_origin.w;
  t0 = 0.0f;
  t1 = tmax;
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
  return t0 <= t1;
}

vec3 transform_direction(int row0, vec3 v) {
  return vec3(dot(uintBitsToFloat(SDF_FETCH(instance_records, row0).xyz), v),
              dot(uintBitsToFloat(SDF_FETCH(instance_records, row0 + 1).xyz), v),
              dot(uintBitsToFloat(SDF_FETCH(instance_records, row0 + 2).xyz), v));
}

// --hit exact: the earliest crossing of the ray with a triangle of `instance` for t in
// [t_lo, t_hi], walking the mesh-grid cells that segment crosses and testing the triangles each
// lists: every crossing inside a cell is found there, since the cell's crossing list holds every
// triangle whose box meets the cell (renderers/sdf/crossing_lists.h). False when
// there is none: the ray passed that surface within epsilon (a silhouette). As
// exact_crossing() in renderers/sdf/exact_hit.cpp.
// The ray is given in the mesh's frame (o + t d, t the world ray's parameter).
bool exact_crossing_in_mesh(vec3 o, vec3 d, uint mesh, float t_lo, float t_hi, out float t_hit, out uint triangle,
                            out vec2 uv) {
  int base = int(mesh) * SDF_MESH_TEXELS;
  uvec4 r0 = SDF_FETCH(mesh_records, base);
  uvec4 r1 = SDF_FETCH(mesh_records, base + 1);
  vec3 origin = uintBitsToFloat(r0.xyz);
  float cell_size = uintBitsToFloat(r0.w);
  uvec3 dims = r1.xyz;
  t_hit = t_hi;
  triangle = SDF_NONE;
  // The segment inside the grid box (outside it the mesh has no triangle).
  float t_cell = t_lo, t_end = t_hi;
  clip_to_box(o, d, origin, origin + vec3(dims) * cell_size, t_cell, t_end);
  uint visited = 0u;
  for (; visited < SDF_EXACT_MAX_CELLS && t_cell <= t_end; ++visited) {
    // Clamped: at the box's faces rounding can put the point a hair outside.
    uvec3 c = uvec3(clamp(floor((o + t_cell * d - origin) / cell_size), vec3(0.0f), vec3(dims - 1u)));
    vec3 cell_lo = origin + vec3(c) * cell_size;
    float t_enter = -3.0e38f, t_exit = 3.0e38f;
    clip_to_box(o, d, cell_lo, cell_lo + cell_size, t_enter, t_exit);
    t_exit += 1e-5f * abs(t_exit);  // rounding of the cell walls
    uvec2 range = SDF_FETCH(crossing_cells, int(r1.w + c.x + dims.x * (c.y + dims.y * c.z))).xy;
    for (int i = int(range.x); i < int(range.y); ++i) {
      uint k = SDF_FETCH(crossing_triangles, i).x;
      int v = 3 * int(k);
      float tk;
      vec2 uvk;
      COUNT(COUNTER_TRIANGLE_TESTS, 1u);
      if (!ray_triangle(o, d, SDF_FETCH(tri_vertices, v).xyz, SDF_FETCH(tri_vertices, v + 1).xyz,
                        SDF_FETCH(tri_vertices, v + 2).xyz, tk, uvk))
        continue;
      // Ties go to the lower triangle index, as in sdf-cpu.
      if (tk >= t_lo && tk <= min(t_exit, t_hi) && (tk < t_hit || (tk == t_hit && k < triangle))) {
        t_hit = tk;
        triangle = k;
        uv = uvk;
      }
    }
    if (triangle != SDF_NONE || t_exit >= t_end) break;
    // At least a ten-thousandth of a cell: a segment starting on a cell wall at t = 0 (a shadow
    // ray leaving its surface) would otherwise pick the cell behind again and again.
    t_cell = max(t_exit, t_cell + max(1e-6f * abs(t_cell), 1e-4f * cell_size / length(d)));
  }
  // Out of cells with segment left: the pixel is cut short, never silently wrong.
  if (triangle == SDF_NONE && visited == SDF_EXACT_MAX_CELLS && t_cell <= t_end) sdf_cut = true;
  return triangle != SDF_NONE;
}

// exact_crossing_in_mesh of a world ray with `instance`.
bool exact_crossing(Ray ray, float t_lo, float t_hi, uint instance, out float t_hit, out uint triangle, out vec2 uv) {
  int record = int(instance) * SDF_INSTANCE_TEXELS;
  vec3 o = transform_point(record + 2, ray.origin);
  vec3 d = transform_direction(record + 2, ray.dir);  // t is the same parameter in both frames
  return exact_crossing_in_mesh(o, d, SDF_FETCH(instance_records, record).w, t_lo, t_hi, t_hit, triangle, uv);
}

#endif
