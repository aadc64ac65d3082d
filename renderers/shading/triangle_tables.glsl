// The scene tables of the triangle backends (tri-aabb, vk-rt; filled by triangle_buffers.h):
// every mesh's triangles concatenated (in the spatial order triangle_buffers.cpp gives them),
// 3 texels per triangle, and an instance table. Texel
// buffers: lavapipe serves divergent texel fetches far faster than divergent storage-buffer
// reads (docs/design.md, "lavapipe, measured").
#ifndef SDFBENCH_TRIANGLE_TABLES_GLSL
#define SDFBENCH_TRIANGLE_TABLES_GLSL
#include "triangle_instance.glsl"
#include "ray_triangle.glsl"

layout(std430, binding = 8) readonly buffer InstanceBlock { TriInstance instances[]; };
layout(binding = 9) uniform textureBuffer tri_vertices;  // v0, v1, v2 (object space)
layout(binding = 10) uniform textureBuffer tri_normals;  // vertex normals n0, n1, n2; n0.w: the mesh's triangle index

vec3 safe_inverse(vec3 d) {
  const float tiny = 1e-30f;
  return vec3(1.0f) / vec3(abs(d.x) > tiny ? d.x : tiny, abs(d.y) > tiny ? d.y : tiny, abs(d.z) > tiny ? d.z : tiny);
}

// Möller–Trumbore against the triangle whose 3 vertex texels start at `base`: t in (0, tmax).
bool hits_triangle(vec3 o, vec3 d, int base, float tmax, out float t, out vec2 uv) {
  COUNT(COUNTER_TRIANGLE_TESTS, 1u);
  return ray_triangle(o, d, texelFetch(tri_vertices, base).xyz, texelFetch(tri_vertices, base + 1).xyz,
                      texelFetch(tri_vertices, base + 2).xyz, t, uv) &&
         t > 0.0f && t < tmax;
}

// The hit of the instance's `slot`-th triangle in these tables at barycentrics uv: the mesh's
// triangle index, material, world shading normal (the vertex normals interpolated, as every
// backend does) and uv.
void fill_triangle_hit(uint instance, uint slot, vec2 uv, float t, inout Hit hit) {
  int base = 3 * (int(instances[instance].info.x) + int(slot));
  vec4 n0 = texelFetch(tri_normals, base);
  vec3 n = interpolate_barycentric(n0.xyz, texelFetch(tri_normals, base + 1).xyz, texelFetch(tri_normals, base + 2).xyz, uv);
  hit.t = t;
  hit.instance = instance;
  hit.prim = floatBitsToUint(n0.w);
  hit.material = instances[instance].info.z;
  hit.normal = normalize(mat3(instances[instance].object_to_world) * n);
  hit.uv = uv;
}

#endif
