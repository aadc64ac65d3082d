// sdf-global's global field in the cache (issue 29), once per scene: its build parameters
// (--global-voxel as asked, auto stored as 0), a global header (origin, voxel, bricks, stored
// count, list entry count, build ms), indirection, atlas (in the parameters' format), coarse
// level (one lower bound per brick, >= 0), list begin (stored + 1 prefix offsets) and list
// instances. Also describe(GlobalFieldParams), which its messages use (global_field.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "renderers/sdf/cache/section_codec.h"
#include "renderers/sdf/cache/section_reader.h"
#include "renderers/sdf/cache/section_writer.h"
#include "renderers/sdf/cache/value_checks.h"
#include "renderers/sdf/sdf_cache_format.h"
#include "renderers/sdf_bricks/brick_field_codec.h"
#include "renderers/sdf_global/global_field.h"

namespace sdfbench::sdf {

std::string describe(const GlobalFieldParams& params) {
  std::ostringstream out;
  out << "--global-voxel ";
  if (params.voxel > 0.0f) out << params.voxel; else out << "auto";
  out << " --brick-band " << params.band << " --sdf-format " << to_string(params.format);
  return out.str();
}

namespace {

struct ParamsRecord {
  float voxel;
  uint32_t band, format, reserved;
};
struct GlobalHeader {
  glm::vec3 origin;
  float voxel;
  glm::uvec3 bricks;
  uint32_t stored;
  uint32_t list_entries;  // list instances
  uint32_t reserved;
  double build_ms;
};
static_assert(sizeof(ParamsRecord) == 16 && sizeof(GlobalHeader) == 48);
enum Section : uint32_t { kParams, kHeader, kIndirection, kAtlas, kCoarse, kListBegin, kListInstances };

void encode(const SdfCacheContents& c, SectionWriter& out) {
  const GlobalFieldStructure& global = c.sdf.get<GlobalFieldStructure>();
  const GlobalFieldParams& p = global.params;
  const GlobalField& g = global.field;
  out.add_one(kParams, 0, ParamsRecord{p.voxel, p.band, static_cast<uint32_t>(p.format), 0});
  out.add_one(kHeader, 0, GlobalHeader{g.field.origin, g.field.voxel, g.field.bricks, static_cast<uint32_t>(g.field.stored_bricks()),
                                       static_cast<uint32_t>(g.list_instances.size()), 0, g.build_ms});
  out.add(kIndirection, 0, g.field.indirection);
  out.add(kAtlas, 0, g.field.atlas);
  out.add(kCoarse, 0, g.field.coarse);
  out.add(kListBegin, 0, g.list_begin);
  out.add(kListInstances, 0, g.list_instances);
}

GlobalFieldParams read_params(const SectionReader& in) {
  const ParamsRecord r = in.single<ParamsRecord>(kParams);
  in.require(r.band >= 1 && r.band <= 16 && valid_format(r.format) && std::isfinite(r.voxel) && r.voxel >= 0.0f,
             "global field parameters");
  GlobalFieldParams p;
  p.voxel = r.voxel;
  p.band = r.band;
  p.format = static_cast<SdfFormat>(r.format);
  return p;
}

// Its coarse level one lower bound per brick (finite, >= 0), and the per-brick instance lists as
// a prefix sum over the stored bricks whose every entry names an instance of the scene.
void decode(const SectionReader& in, SdfCacheContents& c) {
  const std::string what = "global field";
  const GlobalFieldParams params = read_params(in);
  const GlobalHeader h = in.single<GlobalHeader>(kHeader);
  GlobalField g;
  g.voxel_request = params.voxel;
  g.build_ms = h.build_ms;
  g.field = read_field(in, what, {h.origin, h.voxel, h.bricks, h.stored, h.build_ms}, params.format, params.band,
                       {0, kIndirection, kAtlas});
  BrickField& f = g.field;
  f.coarse = in.section<float>(kCoarse);
  f.coarse_at_centres = true;
  in.require(f.coarse.size() == cell_product(h.bricks), what + ": coarse level count differs from its bricks");
  in.require(std::all_of(f.coarse.begin(), f.coarse.end(), [](float v) { return std::isfinite(v) && v >= 0.0f; }),
             what + ": a coarse value is not finite or negative (it is a distance bound)");
  g.list_begin = in.section<uint32_t>(kListBegin);
  g.list_instances = in.section<uint32_t>(kListInstances);
  in.require(g.list_begin.size() == uint64_t{h.stored} + 1, what + ": list begin has " + std::to_string(g.list_begin.size()) +
                                                                " entries for " + std::to_string(h.stored) + " stored bricks");
  in.require(g.list_instances.size() == h.list_entries, what + ": " + std::to_string(g.list_instances.size()) +
                                                            " list instances, header says " + std::to_string(h.list_entries));
  in.require(g.list_begin.front() == 0 && std::is_sorted(g.list_begin.begin(), g.list_begin.end()) &&
                 g.list_begin.back() == g.list_instances.size(),
             what + ": list begin is not a valid prefix sum of the brick lists");
  in.require(std::all_of(g.list_instances.begin(), g.list_instances.end(), [&](uint32_t k) { return k < c.instance_count; }),
             what + ": a brick list names an instance >= " + std::to_string(c.instance_count));
  c.sdf.set(GlobalFieldStructure(params, std::move(g)));
}

std::vector<std::string> summary(const SdfCacheContents& c) {
  const GlobalFieldStructure& global = c.sdf.get<GlobalFieldStructure>();
  const GlobalField& g = global.field;
  const BrickField& f = g.field;
  char line[320];
  std::snprintf(line, sizeof line,
                "global       %ux%ux%u bricks of voxel %g from (%g, %g, %g), %zu stored, %zu list entries, built in %.0f ms", f.bricks.x,
                f.bricks.y, f.bricks.z, f.voxel, f.origin.x, f.origin.y, f.origin.z, f.stored_bricks(), g.list_instances.size(),
                g.build_ms);
  return {"global field " + describe(global.params), line};
}

}  // namespace

const SectionCodec& global_field_codec() {
  static const SectionCodec codec{
      .kind = GlobalFieldStructure::kKind, .name = "global field", .version = 1,
      .sections = {{"global params", sizeof(ParamsRecord), false}, {"global header", sizeof(GlobalHeader), false},
                   {"global indirection", 4, false}, {"global atlas", 1, false}, {"global coarse level", 4, false},
                   {"global list begin", 4, false}, {"global list instances", 4, false}},
      .optional = true, .the_name = "the global field", .encode = encode, .decode = decode, .summary = summary,
  };
  return codec;
}

}  // namespace sdfbench::sdf
