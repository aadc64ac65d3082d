#version 460
#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require
// vk-rt's closest-hit shader: the hit, for vk_rt.rgen to shade.
#include "shading_types.glsl"
#include "vk_rt_payload.glsl"

layout(location = 0) rayPayloadInEXT RtPayload payload;
hitAttributeEXT vec2 barycentrics;  // weights of vertices 1 and 2, as interpolate_barycentric's uv

void main() {
  payload.t = gl_HitTEXT;
  payload.instance = gl_InstanceCustomIndexEXT;
  payload.prim = gl_PrimitiveID;
  payload.barycentrics = barycentrics;
}
