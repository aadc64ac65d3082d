// The scene distance of the SDF backends, as traced_scene_distance() in
// renderers/sdf/traced_distance.cpp (same shortcuts, same work counted): hash cell -> octree
// descent (thesis Algorithm 5.7) -> min over the leaf's instances of the mesh-grid distance in the
// instance's frame, scaled back.
#include "sdf_layout.glsl"
#include "sdf_triangle.glsl"

layout(std140, binding = 8) uniform SdfBlock { SdfParams sdf; };
// The structure's tables, read with SDF_FETCH(table, index). Texel buffers by default (on
// lavapipe 12x faster than storage buffers with divergent indices, Mesa 22.3); SDF_STORAGE_TABLES
// (--storage-tables) binds the same bytes as std430 storage buffers, to measure that on a device.
#ifdef SDF_STORAGE_TABLES
layout(std430, binding = 9) readonly buffer HashCells { uint hash_cells[]; };
layout(std430, binding = 10) readonly buffer OctreeNodes { uint octree_nodes[]; };
layout(std430, binding = 11) readonly buffer InstanceLists { uint instance_lists[]; };
layout(std430, binding = 12) readonly buffer InstanceRecords { uvec4 instance_records[]; };
layout(std430, binding = 13) readonly buffer MeshRecords { uvec4 mesh_records[]; };
layout(std430, binding = 14) readonly buffer GridCells { uvec2 grid_cells[]; };
layout(std430, binding = 15) readonly buffer GridEntries { vec4 grid_entries[]; };
layout(std430, binding = 16) readonly buffer TriVertices { vec4 tri_vertices[]; };
layout(std430, binding = 17) readonly buffer TriNormals { vec4 tri_normals[]; };
#define SDF_FETCH(table, i) table[i]
#else
layout(binding = 9) uniform utextureBuffer hash_cells;        // R32UI node word per hash cell
layout(binding = 10) uniform utextureBuffer octree_nodes;     // R32UI node words below the roots
layout(binding = 11) uniform utextureBuffer instance_lists;   // R32UI count, cell bound, then instances
layout(binding = 12) uniform utextureBuffer instance_records; // RGBA32UI, SDF_INSTANCE_TEXELS each
layout(binding = 13) uniform utextureBuffer mesh_records;     // RGBA32UI, SDF_MESH_TEXELS each
layout(binding = 14) uniform utextureBuffer grid_cells;       // RG32UI (begin, end) per grid cell
layout(binding = 15) uniform textureBuffer grid_entries;      // RGBA32F, SDF_ENTRY_TEXELS per list entry
layout(binding = 16) uniform textureBuffer tri_vertices;      // RGBA32F, 3 per triangle (object space)
layout(binding = 17) uniform textureBuffer tri_normals;       // RGBA32F, 3 per triangle (vertex normals)

#define SDF_FETCH(table, i) texelFetch(table, i)
#endif

const float SDF_FAR = 3.0e38f;  // "no surface": one step by it leaves the hash box

// Time-breakdown variants (tests/bench/sdf_kernel_bench.cpp `breakdown`): SDF_REPEAT_<PART> = 2
// does that part twice, the copy on inputs offset by a run-time zero (sdf.tracing.w, always 0) so
// that the compiler cannot merge the two; the result is the same, the extra time is the part's.
#ifndef SDF_REPEAT_LOCATE
#define SDF_REPEAT_LOCATE 1    // hash cell and octree descent
#endif
#ifndef SDF_REPEAT_BOXES
#define SDF_REPEAT_BOXES 1     // a listed instance's entry, box fetch and box test
#endif
#ifndef SDF_REPEAT_INSTANCE
#define SDF_REPEAT_INSTANCE 1  // an evaluated instance's transform, mesh record and grid cell
#endif
#ifndef SDF_REPEAT_SCAN
#define SDF_REPEAT_SCAN 1      // a list entry's first texel and early-stop test
#endif
#ifndef SDF_REPEAT_DISTANCE
#define SDF_REPEAT_DISTANCE 1  // a point-triangle distance: the entry's other texels and closest point
#endif
#ifndef SDF_REPEAT_EXACT
#define SDF_REPEAT_EXACT 1     // --hit exact's ray-triangle crossing search after a convergence
#endif
#define SDF_ZERO int(floatBitsToUint(sdf.tracing.w))

struct SceneDistance {
  float distance;
  uint instance;  // the nearest listed instance; SDF_NONE outside the hash box or in an empty leaf
  uint triangle;  // global triangle index; SDF_NONE when the distance is only a bound (SDF_FAR_TRIANGLE: a far cell's)
};

float box_distance(vec3 p, vec3 lo, vec3 hi) {
  return length(max(max(lo - p, p - hi), vec3(0.0f)));
}

vec3 fetch_triangle_vertex(uint triangle, int k) {
  return SDF_FETCH(tri_vertices, int(3u * triangle) + k).xyz;
}

// Affine transform by three RGBA32UI texels holding the matrix rows as float bits.
vec3 transform_point(int row0, vec3 p) {
  vec4 r0 = uintBitsToFloat(SDF_FETCH(instance_records, row0));
  vec4 r1 = uintBitsToFloat(SDF_FETCH(instance_records, row0 + 1));
  vec4 r2 = uintBitsToFloat(SDF_FETCH(instance_records, row0 + 2));
  return vec3(dot(r0.xyz, p) + r0.w, dot(r1.xyz, p) + r1.w, dot(r2.xyz, p) + r2.w);
}

// Vertex k of list entry `entry`.
vec3 entry_vertex(int entry, int k) {
  return SDF_FETCH(grid_entries, SDF_ENTRY_TEXELS * entry + k).xyz;
}

// grid_distance() in renderers/sdf/mesh_distance_grid.cpp, object space: inside the grid box the
// min over the cell's listed triangles (exact), or a far cell's bound; outside, the distance to
// the mesh bounds.
float mesh_distance(uint mesh, vec3 p, out uint triangle) {
  int base = int(mesh) * SDF_MESH_TEXELS;
  uvec4 r0 = SDF_FETCH(mesh_records, base);
  uvec4 r1 = SDF_FETCH(mesh_records, base + 1);
  for (int r = 1; r < SDF_REPEAT_INSTANCE; ++r) {
    r0 = min(r0, SDF_FETCH(mesh_records, base + r * SDF_ZERO));
    r1 = min(r1, SDF_FETCH(mesh_records, base + 1 + r * SDF_ZERO));
  }
  vec3 origin = uintBitsToFloat(r0.xyz);
  float cell_size = uintBitsToFloat(r0.w);
  uvec3 dims = r1.xyz;
  vec3 hi = origin + vec3(dims) * cell_size;
  triangle = SDF_NONE;
  if (any(lessThan(p, origin)) || any(greaterThan(p, hi))) {
    vec3 bounds_min = uintBitsToFloat(SDF_FETCH(mesh_records, base + 2).xyz);
    vec3 bounds_max = uintBitsToFloat(SDF_FETCH(mesh_records, base + 3).xyz);
    return box_distance(p, bounds_min, bounds_max);
  }
  uvec3 c = min(uvec3(max(floor((p - origin) / cell_size), vec3(0.0f))), dims - 1u);
  int cell = int(r1.w + c.x + dims.x * (c.y + dims.y * c.z));
  uvec2 range = SDF_FETCH(grid_cells, cell).xy;
  for (int r = 1; r < SDF_REPEAT_INSTANCE; ++r) range = min(range, SDF_FETCH(grid_cells, cell + r * SDF_ZERO).xy);
  float from_centre = length(p - (origin + (vec3(c) + 0.5f) * cell_size));
  // A far cell: its bound less the way from its centre (>= 0.63 cells; no triangle).
  if ((range.x & SDF_FAR_CELL) != 0u) {
    triangle = SDF_FAR_TRIANGLE;
    return uintBitsToFloat(range.x & ~SDF_FAR_CELL) - from_centre;
  }
  float best = SDF_FAR;
  for (int i = int(range.x); i < int(range.y); ++i) {
    vec4 first = SDF_FETCH(grid_entries, SDF_ENTRY_TEXELS * i);
    for (int r = 1; r < SDF_REPEAT_SCAN; ++r) first = min(first, SDF_FETCH(grid_entries, SDF_ENTRY_TEXELS * i + r * SDF_ZERO));
    // past_the_best() in mesh_distance_grid.h: no later entry can come nearer than the best.
    float lower = first.w - from_centre;
    if (lower > 0.0f && lower * lower > best * 1.0001f) break;
    COUNT(COUNTER_TRIANGLE_EVALS, 1u);
    vec4 second = SDF_FETCH(grid_entries, SDF_ENTRY_TEXELS * i + 1);
    uint t = floatBitsToUint(second.w);
    float d2 = distance_squared(p, closest_on_triangle(p, first.xyz, second.xyz, entry_vertex(i, 2)));
    for (int r = 1; r < SDF_REPEAT_DISTANCE; ++r)
      d2 = min(d2, distance_squared(p, closest_on_triangle(p, first.xyz, entry_vertex(i + r * SDF_ZERO, 1),
                                                           entry_vertex(i + r * SDF_ZERO, 2))));
    // Ties go to the lower triangle index, as in the CPU's ascending lists.
    if (d2 < best || (d2 == best && t < triangle)) {
      best = d2;
      triangle = t;
    }
  }
  return sqrt(best);
}

// Set when a descent went deeper than SDF_MAX_OCTREE_DEPTH (the node words are not a tree of
// at most that depth): the pixel is cut short (TRAVERSAL_OVERFLOW in sdf_trace.comp).
bool sdf_cut = false;

// The node word of the octree leaf holding p (inside the hash box): hash cell, then descent
// (thesis Algorithm 5.7), or, past SDF_MAX_OCTREE_DEPTH levels, sdf_cut and the first leaf list.
// `zero` is 0 (SDF_REPEAT_LOCATE's copies pass SDF_ZERO multiples).
// (Keeping the last leaf and skipping the descent while p stays in it was measured 8 % slower on
// lavapipe: the state it keeps costs more than the fetches it saves.)
uint leaf_word(vec3 p, int zero, out vec3 node_lo, out vec3 node_hi) {
  vec3 lo = sdf.hash_origin.xyz;
  float cell_size = sdf.hash_origin.w;
  uvec3 dims = sdf.hash_dims.xyz;
  uvec3 c = min(uvec3(max((p - lo) / cell_size, vec3(0.0f))), dims - 1u);
  uint cell = c.x + dims.x * (c.y + dims.y * c.z);
  node_lo = lo + vec3(c) * cell_size;
  node_hi = lo + vec3(c + 1u) * cell_size;
  uint word = SDF_FETCH(hash_cells, int(cell) + zero).x;
  for (uint level = 0u; (word & SDF_LEAF_BIT) == 0u; ++level) {
    if (level == SDF_MAX_OCTREE_DEPTH) {
      sdf_cut = true;
      return SDF_LEAF_BIT;
    }
    vec3 mid = 0.5f * (node_lo + node_hi);
    bvec3 upper = greaterThanEqual(p, mid);
    node_lo = mix(node_lo, mid, upper);
    node_hi = mix(mid, node_hi, upper);
    uint k = (upper.x ? 1u : 0u) | (upper.y ? 2u : 0u) | (upper.z ? 4u : 0u);
    word = SDF_FETCH(octree_nodes, int(word + k) + zero).x;
  }
  return word;
}

// The leaf holding p (inside the hash box) and its box.
uint find_leaf(vec3 p, out vec3 node_lo, out vec3 node_hi) {
  uint word = leaf_word(p, 0, node_lo, node_hi);
  for (int r = 1; r < SDF_REPEAT_LOCATE; ++r) {
    vec3 lo_copy, hi_copy;
    word = min(word, leaf_word(p, r * SDF_ZERO, lo_copy, hi_copy));
  }
  return word;
}

// --cell-bound: the leaf's least distance to a listed instance's box (0 without the option).
float leaf_bound(uint word) {
  return uintBitsToFloat(SDF_FETCH(instance_lists, int(word & ~SDF_LEAF_BIT) + 1).x);
}

// The scene distance at p (inside the hash box) from the instances the leaf `word` lists. (One
// flattened loop over the instances and their entries, Aila & Laine 2009's answer to divergent
// inner loops, gave the same results 6 % slower on lavapipe.)
SceneDistance leaf_distance(vec3 p, uint word) {
  int list = int(word & ~SDF_LEAF_BIT);
  uint count = SDF_FETCH(instance_lists, list).x;
  SceneDistance best = SceneDistance(SDF_FAR, SDF_NONE, SDF_NONE);
  for (uint k = 0u; k < count; ++k) {
    uint i = SDF_FETCH(instance_lists, list + 2 + int(k)).x;
    int record = int(i) * SDF_INSTANCE_TEXELS;
    // Skip an instance whose box is no nearer than the best so far: its distance cannot win
    // (the CPU keeps the first strict minimum too), and its transform and triangles go unread.
    uvec4 box_min = SDF_FETCH(instance_records, record);
    uvec4 box_max = SDF_FETCH(instance_records, record + 1);
    for (int r = 1; r < SDF_REPEAT_BOXES; ++r) {
      box_min = min(box_min, SDF_FETCH(instance_records, record + r * SDF_ZERO));
      box_max = min(box_max, SDF_FETCH(instance_records, record + 1 + r * SDF_ZERO));
    }
    COUNT(COUNTER_AABB_TESTS, 1u);
    if (box_distance(p, uintBitsToFloat(box_min.xyz), uintBitsToFloat(box_max.xyz)) >= best.distance) continue;
    COUNT(COUNTER_INSTANCE_EVALS, 1u);
    uint triangle;
    vec3 q = transform_point(record + 2, p);
    for (int r = 1; r < SDF_REPEAT_INSTANCE; ++r) q = min(q, transform_point(record + 2 + r * SDF_ZERO, p));
    float d = mesh_distance(box_min.w, q, triangle) * uintBitsToFloat(box_max.w);
    if (d < best.distance) best = SceneDistance(d, i, triangle);
  }
  return best;
}

