#include "renderers/sdf_vk/brick_gpu_arrays.h"

#include <bit>
#include <cstring>
#include <limits>

#include <glm/gtc/packing.hpp>

#include "util/error.h"

namespace sdfbench {
namespace {

uint32_t bits(float f) { return std::bit_cast<uint32_t>(f); }

uint32_t index32(size_t value, const char* what) {
  if (value >= std::numeric_limits<uint32_t>::max())
    throw Error(std::string("the brick fields have too many ") + what + " for the kernel's 32-bit indices; use fewer --voxels");
  return static_cast<uint32_t>(value);
}

}  // namespace

static_assert(sdf::kEmptyBrick == 0xffffffffu, "BRICK_EMPTY in brick_sample.glsl");

BrickGpuArrays flatten_brick_fields(const std::vector<sdf::BrickField>& fields) {
  BrickGpuArrays out;
  if (!fields.empty()) out.format = fields.front().format;
  for (const sdf::BrickField& field : fields) {
    if (field.format != out.format) throw Error("internal: brick fields of one scene in different formats");
    const uint32_t first_brick = index32(out.slots.size(), "bricks");
    const uint32_t first_slot = index32(out.atlas.size() / (sdf::kBrickSamples * sdf::bytes_per_sample(out.format)), "stored bricks");
    const uint32_t first_coarse = index32(out.coarse.size(), "coarse samples");
    // The lattice box lies the band and one voxel outside the mesh bounds on every side (brick_field.cpp).
    const float margin = field.band + field.voxel;
    out.records.emplace_back(bits(field.origin.x), bits(field.origin.y), bits(field.origin.z), bits(field.voxel));
    out.records.emplace_back(field.bricks, first_brick);
    out.records.emplace_back(first_coarse, bits(field.band), bits(field.quantization), bits(margin));
    for (uint32_t slot : field.indirection) out.slots.push_back(slot == sdf::kEmptyBrick ? slot : first_slot + slot);
    out.atlas.insert(out.atlas.end(), field.atlas.begin(), field.atlas.end());
    out.coarse.insert(out.coarse.end(), field.coarse.begin(), field.coarse.end());
    index32(out.atlas.size() / sdf::bytes_per_sample(out.format), "samples");
  }
  return out;
}

namespace shading {

float BrickCpuSampler::brick_value(int i) const {
  const size_t k = size_t(i);
  switch (arrays_.format) {
    case sdf::SdfFormat::f32: {
      float v;
      std::memcpy(&v, &arrays_.atlas[4 * k], 4);
      return v;
    }
    case sdf::SdfFormat::f16: {
      uint16_t h;
      std::memcpy(&h, &arrays_.atlas[2 * k], 2);
      return glm::unpackHalf1x16(h);
    }
    case sdf::SdfFormat::u8: return float(arrays_.atlas[k]) / 255.0f;
  }
  return 0.0f;
}

}  // namespace shading
}  // namespace sdfbench
