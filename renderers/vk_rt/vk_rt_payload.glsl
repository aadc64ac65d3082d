// What vk-rt's closest-hit shader hands the ray-generation shader: the hit of a traceRayEXT.
#ifndef SDFBENCH_VK_RT_PAYLOAD_GLSL
#define SDFBENCH_VK_RT_PAYLOAD_GLSL

struct RtPayload {
  float t;
  uint instance;  // instanceCustomIndex (the scene's instance id); NO_INSTANCE: the ray missed
  uint prim;      // triangle index within the mesh
  vec2 barycentrics;
};

#endif
