// The scene hash in the cache: its build parameters, a hash header (origin, cell size, dims,
// build ms), cell_root, the octree nodes and the instance lists.
#include <algorithm>
#include <cstdio>

#include "renderers/sdf/cache/section_codec.h"
#include "renderers/sdf/cache/section_reader.h"
#include "renderers/sdf/cache/section_writer.h"
#include "renderers/sdf/cache/value_checks.h"
#include "renderers/sdf/sdf_cache_format.h"

namespace sdfbench::sdf {
namespace {

constexpr uint64_t kMaxCachedHashCells = 1ull << 30;

struct ParamsRecord {
  float hash_cell;
  uint32_t octree_depth, octree_min_objects;
  float octree_min_size;
  uint32_t lists, reserved;
};
struct HashHeader {
  glm::vec3 origin;
  float cell_size;
  glm::uvec3 dims;
  uint32_t reserved;
  double build_ms;
};
static_assert(sizeof(ParamsRecord) == 24 && sizeof(HashHeader) == 40 && sizeof(OctreeNode) == 16);
enum Section : uint32_t { kParams, kHashHeader, kCellRoot, kNodes, kInstanceLists };

void encode(const SdfCacheContents& c, SectionWriter& out) {
  const SceneHash& hash = c.sdf.hash;
  const SceneHashParams& p = hash.params;
  out.add_one(kParams, 0, ParamsRecord{p.hash_cell, p.octree_depth, p.octree_min_objects, p.octree_min_size,
                                      static_cast<uint32_t>(p.lists), 0});
  out.add_one(kHashHeader, 0, HashHeader{hash.origin, hash.cell_size, hash.dims, 0, hash.build_ms});
  out.add(kCellRoot, 0, hash.cell_root);
  out.add(kNodes, 0, hash.nodes);
  out.add(kInstanceLists, 0, hash.instance_lists);
}

// Enum fields are checked as raw integers before they become enums.
SceneHashParams read_params(const SectionReader& in) {
  const ParamsRecord r = in.single<ParamsRecord>(kParams);
  in.require(r.lists <= static_cast<uint32_t>(ListRule::Thesis), "list rule parameter");
  in.require(positive_finite(r.hash_cell), "hash cell parameter");
  in.require(r.octree_depth <= 16, "octree depth parameter");
  in.require(r.octree_min_objects >= 1, "octree min objects parameter");
  in.require(positive_finite(r.octree_min_size), "octree min size parameter");
  SceneHashParams p;
  p.hash_cell = r.hash_cell;
  p.octree_depth = r.octree_depth;
  p.octree_min_objects = r.octree_min_objects;
  p.octree_min_size = r.octree_min_size;
  p.lists = static_cast<ListRule>(r.lists);
  return p;
}

void decode(const SectionReader& in, SdfCacheContents& c) {
  const SceneHashParams params = read_params(in);
  const HashHeader h = in.single<HashHeader>(kHashHeader);
  in.require(finite(h.origin) && h.cell_size == params.hash_cell, "scene hash: origin not finite or cell size differs from its parameter");
  in.require(h.dims.x && h.dims.y && h.dims.z && cell_product(h.dims) <= kMaxCachedHashCells, "scene hash: bad dimensions");
  SceneHash& hash = c.sdf.hash;
  hash.origin = h.origin;
  hash.cell_size = h.cell_size;
  hash.dims = h.dims;
  hash.params = params;
  hash.build_ms = h.build_ms;
  hash.cell_root = in.section<uint32_t>(kCellRoot);
  hash.nodes = in.section<OctreeNode>(kNodes);
  hash.instance_lists = in.section<uint32_t>(kInstanceLists);
  in.require(hash.cell_root.size() == cell_product(h.dims), "scene hash: cell_root count differs from its cells");
  const uint64_t node_count = hash.nodes.size();
  in.require(std::all_of(hash.cell_root.begin(), hash.cell_root.end(), [&](uint32_t n) { return n < node_count; }),
             "scene hash: a cell's root node is out of range");
  for (uint64_t i = 0; i < node_count; ++i) {
    const OctreeNode& n = hash.nodes[i];
    const std::string what = "octree node " + std::to_string(i);
    // Children strictly after their parent: every descent terminates.
    in.require(n.first_child == -1 || (n.first_child > 0 && static_cast<uint64_t>(n.first_child) > i &&
                                       static_cast<uint64_t>(n.first_child) + 8 <= node_count),
               what + ": child index out of range");
    in.require(n.depth <= params.octree_depth, what + ": deeper than the octree depth parameter");
    in.require(uint64_t{n.list_begin} + n.list_count <= hash.instance_lists.size(), what + ": instance list out of range");
  }
  in.require(std::all_of(hash.instance_lists.begin(), hash.instance_lists.end(), [&](uint32_t k) { return k < c.instance_count; }),
             "scene hash: an instance list names an instance >= " + std::to_string(c.instance_count));
}

std::vector<std::string> summary(const SdfCacheContents& c) {
  const SceneHash& hash = c.sdf.hash;
  const SceneHashParams& p = hash.params;
  char params[256], structure[256];
  std::snprintf(params, sizeof params, "scene hash   --hash-cell %g --octree-depth %u --octree-min-objects %u --octree-min-size %g --lists %s",
                p.hash_cell, p.octree_depth, p.octree_min_objects, p.octree_min_size, p.lists == ListRule::Exact ? "exact" : "thesis");
  std::snprintf(structure, sizeof structure, "hash         %ux%ux%u cells of %g, %zu octree nodes, built in %.0f ms", hash.dims.x,
                hash.dims.y, hash.dims.z, hash.cell_size, hash.nodes.size(), hash.build_ms);
  return {params, structure};
}

}  // namespace

const SectionCodec& scene_hash_codec() {
  static const SectionCodec codec{
      .kind = 2, .name = "scene hash", .version = 1,
      .sections = {{"hash params", sizeof(ParamsRecord), false}, {"hash header", sizeof(HashHeader), false},
                   {"cell_root", 4, false}, {"octree nodes", sizeof(OctreeNode), false}, {"instance lists", 4, false}},
      .the_name = "the scene hash", .encode = encode, .decode = decode, .summary = summary,
  };
  return codec;
}

}  // namespace sdfbench::sdf
