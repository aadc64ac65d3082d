// Bindings 0-4, common to every Vulkan backend (filled by VulkanFrameRunner).
#include "shading_types.glsl"

layout(std140, binding = 0) uniform FrameBlock { FrameParams frame; };
layout(std430, binding = 1) readonly buffer MaterialBlock { GpuMaterial materials[]; };
layout(std430, binding = 2) readonly buffer LightBlock { GpuLight lights[]; };
layout(std430, binding = 3) writeonly buffer ColorBlock { vec4 out_color[]; };
layout(std430, binding = 4) writeonly buffer AovBlock { GpuAov out_aov[]; };
