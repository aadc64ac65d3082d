#version 460
#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require
// vk-rt's miss shader.
#include "shading_types.glsl"
#include "vk_rt_payload.glsl"

layout(location = 0) rayPayloadInEXT RtPayload payload;

void main() {
  payload.instance = NO_INSTANCE;
}
