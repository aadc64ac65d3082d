// Entry point shared by the Vulkan backends. The backend's .comp file declares its own
// scene bindings (binding >= 8) and closest_hit/any_hit, then includes this file.
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(push_constant) uniform TilePush {
  uvec4 tile;  // xy: pixel offset of this dispatch's tile
} push;

#include "shading.glsl"

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy + push.tile.xy;
  if (pixel.x >= frame.image.x || pixel.y >= frame.image.y) return;
  PixelAov aov;
  vec4 color = shade_pixel(pixel, aov);
  uint index = pixel.y * frame.image.x + pixel.x;
  out_color[index] = color;
  out_aov[index].normal_depth = vec4(aov.normal, aov.depth);
  out_aov[index].ids = uvec4(aov.instance, aov.prim, aov.rays, 0u);
}
