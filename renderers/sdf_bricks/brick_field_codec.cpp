// sdf-bricks' brick fields in the cache (issue 28): their build parameters, then per mesh a brick
// header (origin, voxel, bricks, stored count, build ms), indirection, atlas (bytes in the
// parameters' format) and coarse level (signed, finite, at the brick corners). Also the brick
// format's reader that the global field's codec shares (brick_field_codec.h).
#include "renderers/sdf_bricks/brick_field_codec.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "renderers/sdf/cache/section_codec.h"
#include "renderers/sdf/cache/section_reader.h"
#include "renderers/sdf/cache/section_writer.h"
#include "renderers/sdf/cache/value_checks.h"
#include "renderers/sdf/sdf_cache_format.h"

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

namespace {

struct ParamsRecord {
  uint32_t voxels, band, format, reserved;
};
struct BrickHeader {
  glm::vec3 origin;
  float voxel;
  glm::uvec3 bricks;
  uint32_t stored;
  double build_ms;
};
static_assert(sizeof(ParamsRecord) == 16 && sizeof(BrickHeader) == 40);
enum Section : uint32_t { kParams, kHeader, kIndirection, kAtlas, kCoarse };

void encode(const SdfCacheContents& c, SectionWriter& out) {
  const BrickFields& bricks = c.sdf.get<BrickFields>();
  const BrickFieldParams& p = bricks.params;
  out.add_one(kParams, 0, ParamsRecord{p.voxels, p.band, static_cast<uint32_t>(p.format), 0});
  for (uint32_t m = 0; m < c.sdf.mesh_grids.size(); ++m) {
    const BrickField& f = bricks.fields.at(m);
    out.add_one(kHeader, m, BrickHeader{f.origin, f.voxel, f.bricks, static_cast<uint32_t>(f.stored_bricks()), f.build_ms});
    out.add(kIndirection, m, f.indirection);
    out.add(kAtlas, m, f.atlas);
    out.add(kCoarse, m, f.coarse);
  }
}

BrickFieldParams read_params(const SectionReader& in) {
  const ParamsRecord r = in.single<ParamsRecord>(kParams);
  in.require(r.voxels >= 4 && r.voxels <= kMaxVoxels && r.band >= 1 && r.band <= 16 && valid_format(r.format),
             "brick field parameters");
  return {r.voxels, r.band, static_cast<SdfFormat>(r.format)};
}

BrickField read_bricks(const SectionReader& in, uint32_t mesh, const BrickFieldParams& params) {
  const std::string what = "mesh " + std::to_string(mesh) + " brick field";
  const BrickHeader h = in.single<BrickHeader>(kHeader, mesh);
  BrickField f = read_field(in, what, {h.origin, h.voxel, h.bricks, h.stored, h.build_ms}, params.format, params.band,
                            {mesh, kIndirection, kAtlas});
  f.coarse = in.section<float>(kCoarse, mesh);
  in.require(f.coarse.size() == cell_product(h.bricks + 1u), what + ": coarse level count differs from its brick corners");
  in.require(std::all_of(f.coarse.begin(), f.coarse.end(), [](float v) { return std::isfinite(v); }),
             what + ": non-finite coarse value");
  return f;
}

void decode(const SectionReader& in, SdfCacheContents& c) {
  const BrickFieldParams params = read_params(in);
  std::vector<BrickField> fields;
  for (uint32_t m = 0; m < in.mesh_count(); ++m) fields.push_back(read_bricks(in, m, params));
  c.sdf.set(BrickFields(params, std::move(fields)));
}

std::vector<std::string> summary(const SdfCacheContents& c) {
  const BrickFields& bricks = c.sdf.get<BrickFields>();
  std::vector<std::string> lines{"brick fields " + describe(bricks.params)};
  for (size_t i = 0; i < bricks.fields.size(); ++i) {
    const BrickField& f = bricks.fields[i];
    char line[256];
    std::snprintf(line, sizeof line, "bricks %-5zu %ux%ux%u bricks of voxel %g, %zu stored, built in %.0f ms", i, f.bricks.x,
                  f.bricks.y, f.bricks.z, f.voxel, f.stored_bricks(), f.build_ms);
    lines.push_back(line);
  }
  return lines;
}

}  // namespace

const SectionCodec& brick_field_codec() {
  static const SectionCodec codec{
      .kind = BrickFields::kKind, .name = "brick fields", .version = 1,
      .sections = {{"brick params", sizeof(ParamsRecord), false}, {"brick header", sizeof(BrickHeader), true},
                   {"brick indirection", 4, true}, {"brick atlas", 1, true}, {"brick coarse level", 4, true}},
      .optional = true, .the_name = "brick fields", .encode = encode, .decode = decode, .summary = summary,
  };
  return codec;
}

}  // namespace sdfbench::sdf
