#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
// The sampled fields' sampling code run on the device at given points, through the kernels' own
// fetch path (BRICK_SAMPLER: the hardware's filter), so that a test can hold what the device
// returns against brute force (renderers/sdf_bricks/brick_sampler_probe_test.cpp). Not used by any backend.
#include "shading_types.glsl"
#include "sdf_layout.glsl"

layout(std140, binding = 8) uniform SdfBlock { SdfParams sdf; };
#include "brick_field_bindings.glsl"

layout(local_size_x = 64) in;

layout(push_constant) uniform ProbePush {
  uint points;
  uint mesh;
} push;

layout(std430, binding = 0) readonly buffer ProbePoints { vec4 probe_points[]; };
layout(std430, binding = 1) writeonly buffer ProbeSamples { vec4 probe_samples[]; };  // bound, value, stored, 0

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= push.points) return;
  FieldSample s = sample_field(brick_field_info(push.mesh), probe_points[i].xyz);
  probe_samples[i] = vec4(s.bound, s.value, s.stored ? 1.0f : 0.0f, 0.0f);
}
