// The scene distance of the SDF backends, as traced_scene_distance() in
// renderers/sdf/traced_distance.cpp (same shortcuts, same work counted): hash cell -> octree
// descent (thesis Algorithm 5.7) -> min over the leaf's instances of the mesh-grid distance in the
// instance's frame, scaled back.
#include "sdf_layout.glsl"
#include "sdf_triangle.glsl"

layout(std140, binding = 8) uniform SdfBlock { SdfParams sdf; };
layout(binding = 9) uniform utextureBuffer hash_cells;        // R32UI node word per hash cell
layout(binding = 10) uniform utextureBuffer octree_nodes;     // R32UI node words below the roots
layout(binding = 11) uniform utextureBuffer instance_lists;   // R32UI count, then instances
layout(binding = 12) uniform utextureBuffer instance_records; // RGBA32UI, SDF_INSTANCE_TEXELS each
layout(binding = 13) uniform utextureBuffer mesh_records;     // RGBA32UI, SDF_MESH_TEXELS each
layout(binding = 14) uniform utextureBuffer grid_cells;       // RG32UI (begin, end) per grid cell
layout(binding = 15) uniform utextureBuffer grid_triangles;   // R32UI global triangle indices
layout(binding = 16) uniform textureBuffer tri_vertices;      // RGBA32F, 3 per triangle (object space)
layout(binding = 17) uniform textureBuffer tri_normals;       // RGBA32F, 3 per triangle (vertex normals)
layout(binding = 18) uniform textureBuffer tri_spheres;       // RGBA32F bounding sphere per triangle

const float SDF_FAR = 3.0e38f;  // "no surface": one step by it leaves the hash box

struct SceneDistance {
  float distance;
  uint instance;  // the nearest listed instance; SDF_NONE outside the hash box or in an empty leaf
  uint triangle;  // global triangle index; SDF_NONE when the distance is only a bound
};

float box_distance(vec3 p, vec3 lo, vec3 hi) {
  return length(max(max(lo - p, p - hi), vec3(0.0f)));
}

vec3 fetch_triangle_vertex(uint triangle, int k) {
  return texelFetch(tri_vertices, int(3u * triangle) + k).xyz;
}

// Affine transform by three RGBA32UI texels holding the matrix rows as float bits.
vec3 transform_point(int row0, vec3 p) {
  vec4 r0 = uintBitsToFloat(texelFetch(instance_records, row0));
  vec4 r1 = uintBitsToFloat(texelFetch(instance_records, row0 + 1));
  vec4 r2 = uintBitsToFloat(texelFetch(instance_records, row0 + 2));
  return vec3(dot(r0.xyz, p) + r0.w, dot(r1.xyz, p) + r1.w, dot(r2.xyz, p) + r2.w);
}

// grid_distance() in renderers/sdf/mesh_distance_grid.cpp, object space: inside the grid box the
// min over the cell's listed triangles (exact); outside, the distance to the mesh bounds.
float mesh_distance(uint mesh, vec3 p, out uint triangle) {
  int base = int(mesh) * SDF_MESH_TEXELS;
  uvec4 r0 = texelFetch(mesh_records, base);
  uvec4 r1 = texelFetch(mesh_records, base + 1);
  vec3 origin = uintBitsToFloat(r0.xyz);
  float cell_size = uintBitsToFloat(r0.w);
  uvec3 dims = r1.xyz;
  vec3 hi = origin + vec3(dims) * cell_size;
  triangle = SDF_NONE;
  if (any(lessThan(p, origin)) || any(greaterThan(p, hi))) {
    vec3 bounds_min = uintBitsToFloat(texelFetch(mesh_records, base + 2).xyz);
    vec3 bounds_max = uintBitsToFloat(texelFetch(mesh_records, base + 3).xyz);
    return box_distance(p, bounds_min, bounds_max);
  }
  uvec3 c = min(uvec3(max(floor((p - origin) / cell_size), vec3(0.0f))), dims - 1u);
  uvec2 range = texelFetch(grid_cells, int(r1.w + c.x + dims.x * (c.y + dims.y * c.z))).xy;
  float best = SDF_FAR;
  for (uint i = range.x; i < range.y; ++i) {
    uint t = texelFetch(grid_triangles, int(i)).x;
    // A triangle whose bounding sphere is farther than the best (with a margin for rounding)
    // cannot win; the lists are sorted nearest first, so most are skipped after one fetch.
    vec4 sphere = texelFetch(tri_spheres, int(t));
    float lower = length(p - sphere.xyz) - sphere.w;
    if (lower > 0.0f && lower * lower > best * 1.0001f) continue;
    COUNT(COUNTER_TRIANGLE_EVALS, 1u);
    vec3 a = fetch_triangle_vertex(t, 0), b = fetch_triangle_vertex(t, 1), v2 = fetch_triangle_vertex(t, 2);
    float d2 = distance_squared(p, closest_on_triangle(p, a, b, v2));
    // Ties go to the lower triangle index, as in the CPU's ascending lists.
    if (d2 < best || (d2 == best && t < triangle)) {
      best = d2;
      triangle = t;
    }
  }
  return sqrt(best);
}

SceneDistance scene_distance(vec3 p) {
  vec3 lo = sdf.hash_origin.xyz;
  float cell_size = sdf.hash_origin.w;
  uvec3 dims = sdf.hash_dims.xyz;
  float outside = box_distance(p, lo, lo + vec3(dims) * cell_size);
  if (outside > 0.0f) return SceneDistance(outside, SDF_NONE, SDF_NONE);
  uvec3 c = min(uvec3(max((p - lo) / cell_size, vec3(0.0f))), dims - 1u);
  vec3 node_lo = lo + vec3(c) * cell_size;
  vec3 node_hi = lo + vec3(c + 1u) * cell_size;
  uint word = texelFetch(hash_cells, int(c.x + dims.x * (c.y + dims.y * c.z))).x;
  while ((word & SDF_LEAF_BIT) == 0u) {
    vec3 mid = 0.5f * (node_lo + node_hi);
    bvec3 upper = greaterThanEqual(p, mid);
    node_lo = mix(node_lo, mid, upper);
    node_hi = mix(mid, node_hi, upper);
    uint k = (upper.x ? 1u : 0u) | (upper.y ? 2u : 0u) | (upper.z ? 4u : 0u);
    word = texelFetch(octree_nodes, int(word + k)).x;
  }
  int list = int(word & ~SDF_LEAF_BIT);
  uint count = texelFetch(instance_lists, list).x;
  SceneDistance best = SceneDistance(SDF_FAR, SDF_NONE, SDF_NONE);
  for (uint k = 0u; k < count; ++k) {
    uint i = texelFetch(instance_lists, list + 1 + int(k)).x;
    int record = int(i) * SDF_INSTANCE_TEXELS;
    // Skip an instance whose box is no nearer than the best so far: its distance cannot win
    // (the CPU keeps the first strict minimum too), and its transform and triangles go unread.
    uvec4 box_min = texelFetch(instance_records, record);
    uvec4 box_max = texelFetch(instance_records, record + 1);
    COUNT(COUNTER_AABB_TESTS, 1u);
    if (box_distance(p, uintBitsToFloat(box_min.xyz), uintBitsToFloat(box_max.xyz)) >= best.distance) continue;
    COUNT(COUNTER_INSTANCE_EVALS, 1u);
    uint triangle;
    float d = mesh_distance(box_min.w, transform_point(record + 2, p), triangle) * uintBitsToFloat(box_max.w);
    if (d < best.distance) best = SceneDistance(d, i, triangle);
  }
  return best;
}
