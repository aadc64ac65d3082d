#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
// The device's ceiling for the SDF kernels' inner loop (tests/bench/sdf_kernel_bench.cpp
// `ceiling`): every invocation computes the distance from its own point to push.triangles
// triangles with closest_on_triangle(), the SDF kernels' code, at full occupancy. REGISTERS: no
// fetch in the loop (one triangle read before it, moved a little per iteration: arithmetic only);
// COHERENT: all lanes read the same triangle at once; otherwise each lane reads a different one
// (the divergent gather the kernels do); STORAGE: those reads from a storage buffer, not a texel
// buffer.
#include "sdf_triangle.glsl"

layout(local_size_x = 64) in;

layout(push_constant) uniform CeilingPush {
  vec4 box_min;  // xyz: query box corner, w: edge
  uint triangles;
  uint table_size;
} push;

layout(binding = 0) uniform textureBuffer vertices;  // RGBA32F, 3 per triangle
layout(std430, binding = 1) buffer Result {
  float nearest[];
};
layout(std430, binding = 2) readonly buffer Vertices {  // the same table as a storage buffer
  vec4 vertex_data[];
};
#ifdef STORAGE
#define FETCH_VERTEX(i) vertex_data[i]
#else
#define FETCH_VERTEX(i) texelFetch(vertices, i)
#endif

// A fixed pseudo-random point per invocation (PCG hash), uniform in the query box.
uint pcg(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

void main() {
  uint id = gl_GlobalInvocationID.x;
  vec3 u = vec3(pcg(3u * id), pcg(3u * id + 1u), pcg(3u * id + 2u)) / 4294967295.0f;
  vec3 p = push.box_min.xyz + push.box_min.w * u;
  float best = 3.0e38f;
#ifdef REGISTERS
  vec3 a0 = texelFetch(vertices, 0).xyz, b0 = texelFetch(vertices, 1).xyz, c0 = texelFetch(vertices, 2).xyz;
#endif
  for (uint i = 0u; i < push.triangles; ++i) {
#if defined(REGISTERS)
    vec3 shift = vec3(float(i & 15u), float((i >> 4u) & 15u), float((i >> 8u) & 15u)) * (0.0625f * push.box_min.w);
    vec3 a = a0 + shift, b = b0 + shift, c = c0 + shift;
#else
#ifdef COHERENT
    uint t = i % push.table_size;
#else
    uint t = (i + 977u * id) % push.table_size;
#endif
    vec3 a = FETCH_VERTEX(int(3u * t)).xyz;
    vec3 b = FETCH_VERTEX(int(3u * t + 1u)).xyz;
    vec3 c = FETCH_VERTEX(int(3u * t + 2u)).xyz;
#endif
    vec3 q = closest_on_triangle(p, a, b, c);
    best = min(best, distance_squared(p, q));
  }
  nearest[id] = sqrt(best);
}
