// Bindings 0-5 and 30-31, common to every Vulkan backend (filled by VulkanFrameRunner; 6-7:
// render_main.glsl; COUNTERS_BINDING: work_counters.glsl). The implicit objects sit at 30-31,
// clear of the backends' own bindings (8 on).
#include "shading_types.glsl"
#include "work_counters.glsl"

layout(std140, binding = 0) uniform FrameBlock { FrameParams frame; };
layout(std430, binding = 1) readonly buffer MaterialBlock { GpuMaterial materials[]; };
layout(std430, binding = 2) readonly buffer LightBlock { GpuLight lights[]; };
layout(std430, binding = 3) writeonly buffer ColorBlock { vec4 out_color[]; };
layout(std430, binding = 4) writeonly buffer AovBlock { GpuAov out_aov[]; };
layout(binding = 5) uniform textureBuffer texels;  // image textures, linear RGBA (Scene::texels)
layout(std430, binding = 30) readonly buffer ImplicitObjectBlock { GpuImplicitObject implicit_objects[]; };
layout(std430, binding = 31) readonly buffer ImplicitNodeBlock { GpuImplicitNode implicit_nodes[]; };

vec4 texel_at(uint index) {
  return texelFetch(texels, int(index));
}
