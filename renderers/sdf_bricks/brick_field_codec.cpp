// sdf-bricks' brick fields in the cache (issue 28): their build parameters, then per mesh a brick
// header (origin, voxel, bricks, stored count, build ms), indirection, atlas (bytes in the
// parameters' format) and coarse level (signed, finite, at the brick corners).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "renderers/sdf/cache/field_sections.h"
#include "renderers/sdf/cache/section_codec.h"
#include "renderers/sdf/cache/section_reader.h"
#include "renderers/sdf/cache/section_writer.h"
#include "renderers/sdf/cache/value_checks.h"
#include "renderers/sdf/sdf_cache_format.h"

namespace sdfbench::sdf {
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
  const BrickFieldParams& p = *c.sdf.brick_params;
  out.add_one(kParams, 0, ParamsRecord{p.voxels, p.band, static_cast<uint32_t>(p.format), 0});
  for (uint32_t m = 0; m < c.sdf.mesh_grids.size(); ++m) {
    const BrickField& f = c.sdf.brick_fields.at(m);
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
  for (uint32_t m = 0; m < in.mesh_count(); ++m) c.sdf.brick_fields.push_back(read_bricks(in, m, params));
  c.sdf.brick_params = params;
}

std::vector<std::string> summary(const SdfCacheContents& c) {
  std::vector<std::string> lines{"brick fields " + describe(*c.sdf.brick_params)};
  for (size_t i = 0; i < c.sdf.brick_fields.size(); ++i) {
    const BrickField& f = c.sdf.brick_fields[i];
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
      .kind = 3, .name = "brick fields", .version = 1,
      .sections = {{"brick params", sizeof(ParamsRecord), false}, {"brick header", sizeof(BrickHeader), true},
                   {"brick indirection", 4, true}, {"brick atlas", 1, true}, {"brick coarse level", 4, true}},
      .optional = true, .the_name = "brick fields",
      .held = [](const SceneSdf& sdf) { return sdf.brick_params.has_value(); }, .encode = encode, .decode = decode,
      .summary = summary,
      .serves = [](const StructureRequest& request) { return std::holds_alternative<BrickFieldParams>(request); },
      .differs = [](const SceneSdf& held, const StructureRequest& request) {
        return field_differs(held.brick_params, request, "brick fields");
      },
  };
  return codec;
}

}  // namespace sdfbench::sdf
