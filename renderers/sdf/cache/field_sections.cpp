#include "renderers/sdf/cache/field_sections.h"

#include <algorithm>
#include <cmath>

#include "renderers/sdf/cache/value_checks.h"

namespace sdfbench::sdf {
namespace {

constexpr uint64_t kMaxBricks = 1ull << 26;

// Stored values within the band, up to the format's quantization (a clamped f16 value may round
// past the band by up to band / 2048); u8 cannot leave it. A NaN fails the comparison.
void check_atlas_values(const SectionReader& in, const BrickField& f, const std::string& what) {
  if (f.format == SdfFormat::u8) return;
  const float limit = f.band + f.quantization;
  const size_t samples = f.atlas.size() / bytes_per_sample(f.format);
  for (size_t i = 0; i < samples; ++i)
    in.require(std::abs(atlas_value(f, i)) <= limit, what + ": an atlas value is not finite or lies beyond the band");
}

}  // namespace

BrickField read_field(const SectionReader& in, const std::string& what, const FieldHeaderValues& h, SdfFormat format,
                      uint32_t band, FieldSectionIndices sections) {
  in.require(finite(h.origin) && positive_finite(h.voxel), what + ": origin or voxel not finite");
  in.require(h.bricks.x && h.bricks.y && h.bricks.z && cell_product(h.bricks) <= kMaxBricks, what + ": bad dimensions");
  in.require(h.stored <= cell_product(h.bricks), what + ": more stored bricks than bricks");
  BrickField f;
  f.origin = h.origin;
  f.voxel = h.voxel;
  f.bricks = h.bricks;
  f.format = format;
  f.band = static_cast<float>(band) * h.voxel;
  f.quantization = brick_quantization(format, f.band);
  f.build_ms = h.build_ms;
  in.require(positive_finite(f.band) && std::isfinite(f.quantization), what + ": band not finite");
  f.indirection = in.section<uint32_t>(sections.indirection, sections.owner);
  in.require(f.indirection.size() == cell_product(h.bricks), what + ": indirection has " + std::to_string(f.indirection.size()) +
                                                                  " entries for " + std::to_string(cell_product(h.bricks)) + " bricks");
  in.require(std::all_of(f.indirection.begin(), f.indirection.end(), [&](uint32_t s) { return s == kEmptyBrick || s < h.stored; }),
             what + ": a brick's atlas index is out of range");
  f.atlas = in.section<uint8_t>(sections.atlas, sections.owner);
  in.require(f.atlas.size() == uint64_t{h.stored} * kBrickSamples * bytes_per_sample(format),
             what + ": atlas of " + std::to_string(f.atlas.size()) + " bytes for " + std::to_string(h.stored) + " bricks");
  check_atlas_values(in, f, what);
  return f;
}

}  // namespace sdfbench::sdf
