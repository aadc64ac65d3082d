// The sampled-field kernels' bindings of their brick fields (sdf_bricks.comp: one per mesh;
// sdf_global.comp: the scene's one) and the accessors brick_sample.glsl reads them by (layout in
// brick_gpu_arrays.h). BRICK_SAMPLER: the atlas as a filtered 3D image; BRICK_U8: 8-bit values.
#ifndef SDFBENCH_BRICK_FIELD_BINDINGS_GLSL
#define SDFBENCH_BRICK_FIELD_BINDINGS_GLSL

layout(binding = 18) uniform utextureBuffer brick_records;  // RGBA32UI, BRICK_FIELD_TEXELS per mesh
layout(binding = 19) uniform utextureBuffer brick_slots;    // R32UI stored-brick index per brick, or BRICK_EMPTY
layout(binding = 21) uniform textureBuffer brick_coarse;    // R32F, one sample per brick corner
#ifdef BRICK_SAMPLER
// The stored bricks side by side in a 3D image (sdf.atlas_bricks per row and slice), filtered by
// the sampler: one fetch per sample instead of eight.
layout(binding = 20) uniform sampler3D brick_atlas;
float brick_filtered(uint slot, vec3 local) {
  uvec3 b = uvec3(slot % sdf.atlas_bricks.x, (slot / sdf.atlas_bricks.x) % sdf.atlas_bricks.y,
                  slot / (sdf.atlas_bricks.x * sdf.atlas_bricks.y));
  return textureLod(brick_atlas, (vec3(b * 8u) + local + 0.5f) * sdf.atlas_inverse_size.xyz, 0.0f).x;
}
float brick_filter_slack(float voxel, float band) { return sdf.options.z * voxel + sdf.options.w * band; }
#else
layout(binding = 20) uniform textureBuffer brick_atlas;     // R32F / R16F / R8_UNORM, 8^3 samples per stored brick
float brick_value(int i) { return texelFetch(brick_atlas, i).x; }
#endif

uvec4 brick_record(int i) { return texelFetch(brick_records, i); }
uint brick_slot(int i) { return texelFetch(brick_slots, i).x; }
float coarse_value(int i) { return texelFetch(brick_coarse, i).x; }
float brick_decode(float raw, float band) {
#ifdef BRICK_U8
  return (raw * 2.0f - 1.0f) * band;
#else
  return raw;
#endif
}
#include "brick_sample.glsl"

#endif
