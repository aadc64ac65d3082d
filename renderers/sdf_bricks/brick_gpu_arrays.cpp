#include "renderers/sdf_bricks/brick_gpu_arrays.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

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
    if (field.format != out.format) throw InternalError("brick fields of one scene in different formats");
    const uint32_t first_brick = index32(out.slots.size(), "bricks");
    const uint32_t first_slot = index32(out.atlas.size() / (sdf::kBrickSamples * sdf::bytes_per_sample(out.format)), "stored bricks");
    const uint32_t first_coarse = index32(out.coarse.size(), "coarse samples");
    // The lattice box lies the band and one voxel outside the mesh bounds on every side (brick_field.cpp).
    const float margin = field.band + field.voxel;
    out.records.emplace_back(bits(field.origin.x), bits(field.origin.y), bits(field.origin.z), bits(field.voxel));
    out.records.emplace_back(field.bricks, first_brick);
    out.records.emplace_back(first_coarse, bits(field.band), bits(field.quantization), bits(margin));
    out.records.emplace_back(field.coarse_at_centres ? 1u : 0u, 0u, 0u, 0u);
    for (uint32_t slot : field.indirection) out.slots.push_back(slot == sdf::kEmptyBrick ? slot : first_slot + slot);
    out.atlas.insert(out.atlas.end(), field.atlas.begin(), field.atlas.end());
    out.coarse.insert(out.coarse.end(), field.coarse.begin(), field.coarse.end());
    index32(out.atlas.size() / sdf::bytes_per_sample(out.format), "samples");
  }
  return out;
}

BrickAtlasImage arrange_atlas_image(const BrickGpuArrays& arrays, uint32_t max_extent) {
  const size_t sample_bytes = sdf::bytes_per_sample(arrays.format);
  const size_t stored = arrays.atlas.size() / (sdf::kBrickSamples * sample_bytes);
  BrickAtlasImage image;
  const uint32_t per_axis = std::max(1u, max_extent / sdf::kBrickSide);
  const uint32_t side = static_cast<uint32_t>(std::ceil(std::cbrt(double(std::max<size_t>(stored, 1)))));
  image.bricks.x = std::min(side, per_axis);
  image.bricks.y = std::min(side, per_axis);
  image.bricks.z = static_cast<uint32_t>((std::max<size_t>(stored, 1) + size_t(image.bricks.x) * image.bricks.y - 1) /
                                         (size_t(image.bricks.x) * image.bricks.y));
  image.extent = image.bricks * sdf::kBrickSide;  // (a z beyond the device's limit: GpuImage3D says so)
  image.texels.assign(size_t(image.extent.x) * image.extent.y * image.extent.z * sample_bytes, 0);
  const size_t row = size_t(image.extent.x), slice = row * image.extent.y;
  for (size_t s = 0; s < stored; ++s) {
    const glm::uvec3 b(s % image.bricks.x, (s / image.bricks.x) % image.bricks.y, s / (size_t(image.bricks.x) * image.bricks.y));
    const glm::uvec3 corner = b * sdf::kBrickSide;
    for (uint32_t z = 0; z < sdf::kBrickSide; ++z)
      for (uint32_t y = 0; y < sdf::kBrickSide; ++y) {
        const size_t from = (s * sdf::kBrickSamples + sdf::kBrickSide * (y + sdf::kBrickSide * z)) * sample_bytes;
        const size_t to = (corner.x + row * (corner.y + y) + slice * (corner.z + z)) * sample_bytes;
        std::memcpy(&image.texels[to], &arrays.atlas[from], sdf::kBrickSide * sample_bytes);
      }
  }
  return image;
}

}  // namespace sdfbench
