#pragma once
// The brick fields of a scene's meshes (renderers/sdf_bricks/brick_field.h) flattened into the texel
// buffers the sdf-bricks kernel reads (layout in brick_sample.glsl), and read back on the CPU
// by the kernel's own sampling code (BrickCpuSampler) for the tests.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "renderers/sdf_bricks/brick_field.h"
#include "renderers/shading/gpu_types.h"

namespace sdfbench {

struct BrickGpuArrays {
  sdf::SdfFormat format = sdf::SdfFormat::f32;  // of every mesh's atlas
  std::vector<glm::uvec4> records;   // BRICK_FIELD_TEXELS per mesh
  std::vector<uint32_t> slots;       // the meshes' indirection tables, concatenated
  std::vector<uint8_t> atlas;        // the meshes' atlases, concatenated (slots index the whole)
  std::vector<float> coarse;         // the meshes' coarse levels, concatenated
};

// Throws Error when a table would not fit the kernel's 32-bit indices.
BrickGpuArrays flatten_brick_fields(const std::vector<sdf::BrickField>& fields);

// --brick-fetch sampler: the stored bricks side by side in a 3D image, `bricks` per axis (x, then
// y, then z: brick s at (s % x, s / x % y, s / (x y))), the image `extent` = 8 x bricks texels.
struct BrickAtlasImage {
  glm::uvec3 bricks{1u};
  glm::uvec3 extent{8u};
  std::vector<uint8_t> texels;  // x fastest, in the arrays' format
};
BrickAtlasImage arrange_atlas_image(const BrickGpuArrays& arrays, uint32_t max_extent);

namespace shading {
// brick_sample.glsl compiled as C++ over flattened arrays: the same arithmetic as the kernel.
class BrickCpuSampler {
 public:
  explicit BrickCpuSampler(const BrickGpuArrays& arrays) : arrays_(arrays) {}

 private:
  const BrickGpuArrays& arrays_;
  uvec4 brick_record(int i) const { return arrays_.records[size_t(i)]; }
  uint brick_slot(int i) const { return arrays_.slots[size_t(i)]; }
  float brick_value(int i) const { return sdf::atlas_texel(arrays_.atlas, arrays_.format, size_t(i)); }
  float coarse_value(int i) const { return arrays_.coarse[size_t(i)]; }
  float brick_decode(float raw, float band) const {
    return arrays_.format == sdf::SdfFormat::u8 ? (raw * 2.0f - 1.0f) * band : raw;
  }

 public:
#include "brick_sample.glsl"
};
}  // namespace shading

}  // namespace sdfbench
