#include "renderers/sdf/sdf_cache_format.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <type_traits>

#include "util/error.h"
#include "util/fnv1a.h"

namespace sdfbench::sdf {
namespace {

static_assert(std::endian::native == std::endian::little, "the cache format is little-endian");
static_assert(sizeof(glm::vec3) == 12 && sizeof(OctreeNode) == 16);

constexpr char kMagic[8] = {'S', 'D', 'F', 'B', 'C', 'A', 'C', 'H'};
constexpr uint32_t kMaxMeshes = 1u << 16;
constexpr uint32_t kMaxInstances = 1u << 24;
constexpr uint64_t kMaxMeshCells = 1ull << 26;  // build_mesh_distance_grid's own limit
constexpr uint64_t kMaxHashCells = 1ull << 30;

struct FileHeader {
  char magic[8];
  uint32_t version, header_bytes;
  uint64_t file_bytes, scene_hash;
  uint32_t mesh_count, instance_count, section_count;
  uint32_t bricks;  // 0: no brick fields; else voxels | band << 16 | (format + 1) << 24
  float mesh_cell_size;
  uint32_t cells_per_extent;
  float margin_cells;
  uint32_t mesh_rule, subdivision;
  float hash_cell;
  uint32_t octree_depth, octree_min_objects;
  float octree_min_size;
  uint32_t lists;
  uint32_t global;     // 0: no global field; else band | (format + 1) << 8
  float global_voxel;  // the global field's voxel request (0: auto); 0 without one
};
struct SectionEntry {
  uint32_t kind, owner, element_bytes, reserved;
  uint64_t offset, count;
};
struct GridHeader {
  glm::vec3 origin;
  float cell_size;
  glm::uvec3 dims;
  uint32_t triangles, vertices, reserved;
  double build_ms;
};
struct HashHeader {
  glm::vec3 origin;
  float cell_size;
  glm::uvec3 dims;
  uint32_t reserved;
  double build_ms;
};
struct BrickHeader {
  glm::vec3 origin;
  float voxel;
  glm::uvec3 bricks;
  uint32_t stored;
  double build_ms;
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
static_assert(sizeof(FileHeader) == kSdfCacheHeaderBytes && sizeof(SectionEntry) == 32 && sizeof(GridHeader) == 48 &&
              sizeof(HashHeader) == 40 && sizeof(BrickHeader) == 40 && sizeof(GlobalHeader) == 48);

enum SectionKind : uint32_t {
  kGridHeader, kCellBegin, kCellTriangles, kFaceNormals, kEdgeNormals, kVertexNormals,  // per mesh
  kHashHeader, kCellRoot, kNodes, kInstanceLists,                                       // scene
  kBrickHeader, kBrickSlots, kBrickAtlas, kBrickCoarse,                                 // per mesh, with brick fields
  kGlobalHeader, kGlobalSlots, kGlobalAtlas, kGlobalCoarse, kGlobalListBegin, kGlobalListInstances,  // scene, with a global field
  kKindCount
};
constexpr uint32_t kMeshKinds = kHashHeader;
constexpr uint32_t kSceneKinds = kBrickHeader - kHashHeader;
constexpr uint32_t kBrickKinds = kGlobalHeader - kBrickHeader;
constexpr uint32_t kGlobalKinds = kKindCount - kGlobalHeader;
constexpr const char* kKindNames[kKindCount] = {"grid header", "cell_begin", "cell_triangles", "face normals",
                                                "edge normals", "vertex normals", "hash header", "cell_root",
                                                "octree nodes", "instance lists", "brick header", "brick indirection",
                                                "brick atlas", "brick coarse level", "global header", "global indirection",
                                                "global atlas", "global coarse level", "global list begin",
                                                "global list instances"};
constexpr uint32_t kElementBytes[kKindCount] = {sizeof(GridHeader), 4, 4, 12, 12, 12, sizeof(HashHeader), 4, 16, 4,
                                                sizeof(BrickHeader), 4, 1, 4, sizeof(GlobalHeader), 4, 1, 4, 4, 4};
bool per_mesh(uint32_t kind) { return kind < kMeshKinds || (kind >= kBrickHeader && kind < kGlobalHeader); }
constexpr uint64_t kMaxBricks = 1ull << 26;

uint32_t brick_word(const std::optional<BrickFieldParams>& p) {
  return p ? p->voxels | p->band << 16 | (static_cast<uint32_t>(p->format) + 1) << 24 : 0;
}
uint32_t global_word(const std::optional<GlobalFieldParams>& p) {
  return p ? p->band | (static_cast<uint32_t>(p->format) + 1) << 8 : 0;
}

uint64_t align8(uint64_t n) { return (n + 7) & ~uint64_t{7}; }

class Writer {
 public:
  template <class T>
  void add(uint32_t kind, uint32_t owner, const std::vector<T>& items) {
    static_assert(std::is_trivially_copyable_v<T>);
    pending_.push_back({kind, owner, items.data(), items.size() * sizeof(T), items.size()});
  }
  template <class T>
  void add_one(uint32_t kind, uint32_t owner, const T& item) {
    pending_.push_back({kind, owner, &item, sizeof(T), 1});
  }
  std::vector<std::byte> finish(FileHeader header) const {
    header.section_count = static_cast<uint32_t>(pending_.size());
    uint64_t offset = align8(sizeof(FileHeader) + pending_.size() * sizeof(SectionEntry));
    std::vector<SectionEntry> table;
    for (const Pending& p : pending_) {
      table.push_back({p.kind, p.owner, kElementBytes[p.kind], 0, offset, p.count});
      offset = align8(offset + p.bytes);
    }
    header.file_bytes = offset + sizeof(uint64_t);
    std::vector<std::byte> out(header.file_bytes, std::byte{0});
    std::memcpy(out.data(), &header, sizeof header);
    std::memcpy(out.data() + sizeof header, table.data(), table.size() * sizeof(SectionEntry));
    for (size_t i = 0; i < pending_.size(); ++i)
      if (pending_[i].bytes) std::memcpy(out.data() + table[i].offset, pending_[i].data, pending_[i].bytes);
    reseal_sdf_cache(out);
    return out;
  }

 private:
  struct Pending {
    uint32_t kind, owner;
    const void* data;
    uint64_t bytes, count;
  };
  std::vector<Pending> pending_;
};

[[noreturn]] void fail_invalid(const std::string& source, const std::string& what) {
  throw Error("SDF cache '" + source + "' is invalid: " + what + " (rebuild it with `sdfbench build --cache`)");
}

// The fixed header against the file's size: what can be checked before the body is read.
FileHeader check_header(std::span<const std::byte> head, uint64_t file_bytes, const std::string& source) {
  if (file_bytes < sizeof(FileHeader) + sizeof(uint64_t) || head.size() < sizeof(FileHeader))
    fail_invalid(source, "file is " + std::to_string(file_bytes) + " bytes, too short for a cache header");
  FileHeader h;
  std::memcpy(&h, head.data(), sizeof h);
  if (std::memcmp(h.magic, kMagic, sizeof kMagic) != 0)
    throw Error("'" + source + "' is not an sdfbench SDF cache (bad magic)");
  if (h.version != kSdfCacheVersion)
    throw Error("SDF cache '" + source + "' has format version " + std::to_string(h.version) + "; this sdfbench reads version " +
                std::to_string(kSdfCacheVersion) + " (rebuild it with `sdfbench build --cache`)");
  if (h.header_bytes != sizeof(FileHeader)) fail_invalid(source, "header size " + std::to_string(h.header_bytes));
  if (h.file_bytes != file_bytes)
    fail_invalid(source, "truncated or extended: header says " + std::to_string(h.file_bytes) + " bytes, file has " +
                             std::to_string(file_bytes));
  return h;
}

// Reads validated sections; every failure is an Error naming the file and the problem.
class Reader {
 public:
  Reader(std::span<const std::byte> bytes, const std::string& source) : bytes_(bytes), source_(source) {}

  [[noreturn]] void fail(const std::string& what) const { fail_invalid(source_, what); }
  void require(bool ok, const std::string& what) const {
    if (!ok) fail(what);
  }

  FileHeader header() {
    const FileHeader h = check_header(bytes_, bytes_.size(), source_);
    uint64_t stored;
    std::memcpy(&stored, bytes_.data() + bytes_.size() - sizeof stored, sizeof stored);
    require(stored == fnv1a64(bytes_.first(bytes_.size() - sizeof stored)), "checksum mismatch (corrupted file)");
    // No meshes or instances is a scene of implicit objects only (its hash is one empty cell).
    require(h.mesh_count <= kMaxMeshes, "mesh count " + std::to_string(h.mesh_count));
    require(h.instance_count <= kMaxInstances, "instance count " + std::to_string(h.instance_count));
    bricks_ = h.bricks != 0;
    global_ = h.global != 0;
    require(h.section_count == h.mesh_count * (kMeshKinds + (bricks_ ? kBrickKinds : 0)) + kSceneKinds + (global_ ? kGlobalKinds : 0),
            "section count " + std::to_string(h.section_count) + " for " + std::to_string(h.mesh_count) + " meshes" +
                (bricks_ ? " with brick fields" : "") + (global_ ? " and a global field" : ""));
    read_table(h);
    return h;
  }

  template <class T>
  std::vector<T> section(uint32_t kind, uint32_t owner) const {
    const SectionEntry& e = entry(kind, owner);
    std::vector<T> items(e.count);
    if (e.count) std::memcpy(items.data(), bytes_.data() + e.offset, e.count * sizeof(T));
    return items;
  }
  template <class T>
  T single(uint32_t kind, uint32_t owner) const {
    const SectionEntry& e = entry(kind, owner);
    require(e.count == 1, name(kind, owner) + " holds " + std::to_string(e.count) + " records, expected 1");
    T item;
    std::memcpy(&item, bytes_.data() + e.offset, sizeof item);
    return item;
  }
  std::vector<SdfCacheSection> describe() const {
    std::vector<SdfCacheSection> out;
    for (const SectionEntry& e : table_)
      out.push_back({name(e.kind, e.owner), e.offset, e.count, e.count * e.element_bytes});
    return out;
  }
  std::string name(uint32_t kind, uint32_t owner) const {
    return per_mesh(kind) ? "mesh " + std::to_string(owner) + " " + kKindNames[kind] : std::string(kKindNames[kind]);
  }

 private:
  void read_table(const FileHeader& h) {
    const uint64_t table_end = sizeof(FileHeader) + uint64_t{h.section_count} * sizeof(SectionEntry);
    const uint64_t payload_end = bytes_.size() - sizeof(uint64_t);
    require(table_end <= payload_end, "section table runs past the end of the file");
    table_.resize(h.section_count);
    std::memcpy(table_.data(), bytes_.data() + sizeof(FileHeader), table_.size() * sizeof(SectionEntry));
    mesh_count_ = h.mesh_count;
    index_.assign(h.section_count, UINT32_MAX);
    for (uint32_t i = 0; i < table_.size(); ++i) {
      const SectionEntry& e = table_[i];
      const std::string where = "section " + std::to_string(i);
      require(known(e.kind), where + " has unknown kind " + std::to_string(e.kind));
      require(per_mesh(e.kind) ? e.owner < h.mesh_count : e.owner == 0, where + " (" + kKindNames[e.kind] + ") has owner " + std::to_string(e.owner));
      require(e.element_bytes == kElementBytes[e.kind], name(e.kind, e.owner) + ": element size " + std::to_string(e.element_bytes));
      require(e.offset % 8 == 0 && e.offset >= table_end && e.offset <= payload_end,
              name(e.kind, e.owner) + ": offset " + std::to_string(e.offset) + " outside the payload");
      require(e.count <= (payload_end - e.offset) / e.element_bytes, name(e.kind, e.owner) + ": " + std::to_string(e.count) +
                                                                          " elements run past the end of the file");
      const size_t slot = slot_of(e.kind, e.owner);
      require(index_[slot] == UINT32_MAX, name(e.kind, e.owner) + " appears twice");
      index_[slot] = i;
    }
    // Every slot is filled (count matched and no duplicates); sections must not overlap.
    std::vector<const SectionEntry*> by_offset;
    for (const SectionEntry& e : table_) by_offset.push_back(&e);
    std::sort(by_offset.begin(), by_offset.end(), [](auto a, auto b) { return a->offset < b->offset; });
    for (size_t i = 1; i < by_offset.size(); ++i) {
      const SectionEntry& a = *by_offset[i - 1];
      require(a.offset + a.count * a.element_bytes <= by_offset[i]->offset,
              name(a.kind, a.owner) + " overlaps " + name(by_offset[i]->kind, by_offset[i]->owner));
    }
  }
  // The kinds this file's header allows: brick kinds only with brick fields, global kinds only
  // with a global field.
  bool known(uint32_t kind) const {
    if (kind < kBrickHeader) return true;
    if (kind < kGlobalHeader) return bricks_;
    return kind < kKindCount && global_;
  }
  // Mesh kinds per mesh, then the scene's, then (with brick fields) the brick kinds per mesh, then
  // (with a global field) the global kinds.
  size_t slot_of(uint32_t kind, uint32_t owner) const {
    const size_t meshes = mesh_count_;
    if (kind < kMeshKinds) return static_cast<size_t>(owner) * kMeshKinds + kind;
    if (kind < kBrickHeader) return meshes * kMeshKinds + (kind - kMeshKinds);
    if (kind < kGlobalHeader) return meshes * kMeshKinds + kSceneKinds + static_cast<size_t>(owner) * kBrickKinds + (kind - kBrickHeader);
    return meshes * (kMeshKinds + (bricks_ ? kBrickKinds : 0)) + kSceneKinds + (kind - kGlobalHeader);
  }
  const SectionEntry& entry(uint32_t kind, uint32_t owner) const { return table_[index_[slot_of(kind, owner)]]; }

  std::span<const std::byte> bytes_;
  std::string source_;
  std::vector<SectionEntry> table_;
  std::vector<uint32_t> index_;  // slot_of(kind, owner) -> table entry
  uint32_t mesh_count_ = 0;
  bool bricks_ = false;
  bool global_ = false;
};

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool positive_finite(float f) { return std::isfinite(f) && f > 0.0f; }

uint64_t cell_product(const glm::uvec3& dims) { return uint64_t{dims.x} * dims.y * dims.z; }

// Enum fields are checked as raw integers before they become enums.
void check_params(const Reader& r, const FileHeader& h) {
  r.require(h.mesh_rule <= static_cast<uint32_t>(MeshGridRule::sphere), "mesh grid rule parameter");
  r.require(h.lists <= static_cast<uint32_t>(ListRule::Thesis), "list rule parameter");
  const MeshGridParams m{h.mesh_cell_size, h.cells_per_extent, h.margin_cells, MeshGridRule::tight, h.subdivision};
  const SceneHashParams s{h.hash_cell, h.octree_depth, h.octree_min_objects, h.octree_min_size, ListRule::Exact};
  r.require(std::isfinite(m.cell_size) && m.cell_size >= 0.0f, "mesh cell size parameter");
  r.require(m.cells_per_extent >= 1 && m.cells_per_extent <= 4096, "cells-per-extent parameter");
  r.require(std::isfinite(m.margin_cells) && m.margin_cells >= 0.0f, "mesh margin parameter");
  r.require(m.subdivision >= 1 && m.subdivision <= 8, "mesh grid subdivision parameter");
  r.require(positive_finite(s.hash_cell), "hash cell parameter");
  r.require(s.octree_depth <= 16, "octree depth parameter");
  r.require(s.octree_min_objects >= 1, "octree min objects parameter");
  r.require(positive_finite(s.octree_min_size), "octree min size parameter");
  if (h.bricks != 0) {
    const uint32_t voxels = h.bricks & 0xffffu, band = (h.bricks >> 16) & 0xffu, format = h.bricks >> 24;
    r.require(voxels >= 4 && voxels <= kMaxVoxels && band >= 1 && band <= 16 && format >= 1 && format <= 3,
              "brick field parameters");
  }
  if (h.global != 0) {
    const uint32_t band = h.global & 0xffu, format = (h.global >> 8) & 0xffu;
    r.require(band >= 1 && band <= 16 && format >= 1 && format <= 3 && (h.global >> 16) == 0 && std::isfinite(h.global_voxel) &&
                  h.global_voxel >= 0.0f,
              "global field parameters");
  } else {
    r.require(h.global_voxel == 0.0f, "global field parameters (a voxel request without a global field)");
  }
}

BrickFieldParams brick_params_of(uint32_t word) {
  return {word & 0xffffu, (word >> 16) & 0xffu, static_cast<SdfFormat>((word >> 24) - 1)};
}
GlobalFieldParams global_params_of(uint32_t word, float voxel) {
  GlobalFieldParams p;
  p.voxel = voxel;
  p.band = word & 0xffu;
  p.format = static_cast<SdfFormat>(((word >> 8) & 0xffu) - 1);
  return p;
}

// Stored values within the band, up to the format's quantization (a clamped f16 value may round
// past the band by up to band / 2048); u8 cannot leave it. A NaN fails the comparison.
void check_atlas_values(const Reader& r, const BrickField& f, const std::string& what) {
  if (f.format == SdfFormat::u8) return;
  const float limit = f.band + f.quantization;
  const size_t samples = f.atlas.size() / bytes_per_sample(f.format);
  for (size_t i = 0; i < samples; ++i)
    r.require(std::abs(atlas_value(f, i)) <= limit, what + ": an atlas value is not finite or lies beyond the band");
}

// What a mesh's brick field and the global field share: the header's values, the indirection and
// the atlas (every index in range, every count what the header implies, values within the band: a
// NaN would stall no march but mislead every bound); band and quantization are recomputed from
// the parameters, never taken from the file.
struct FieldSections {
  uint32_t owner, slots, atlas;  // section owner and kinds
};
BrickField read_field(const Reader& r, const std::string& what, const glm::vec3& origin, float voxel,
                      const glm::uvec3& bricks, uint32_t stored, double build_ms, SdfFormat format, uint32_t band,
                      FieldSections sections) {
  r.require(finite(origin) && positive_finite(voxel), what + ": origin or voxel not finite");
  r.require(bricks.x && bricks.y && bricks.z && cell_product(bricks) <= kMaxBricks, what + ": bad dimensions");
  r.require(stored <= cell_product(bricks), what + ": more stored bricks than bricks");
  BrickField f;
  f.origin = origin;
  f.voxel = voxel;
  f.bricks = bricks;
  f.format = format;
  f.band = static_cast<float>(band) * voxel;
  f.quantization = brick_quantization(format, f.band);
  f.build_ms = build_ms;
  r.require(positive_finite(f.band) && std::isfinite(f.quantization), what + ": band not finite");
  f.indirection = r.section<uint32_t>(sections.slots, sections.owner);
  r.require(f.indirection.size() == cell_product(bricks), what + ": indirection has " + std::to_string(f.indirection.size()) +
                                                                " entries for " + std::to_string(cell_product(bricks)) + " bricks");
  r.require(std::all_of(f.indirection.begin(), f.indirection.end(), [&](uint32_t s) { return s == kEmptyBrick || s < stored; }),
            what + ": a brick's atlas index is out of range");
  f.atlas = r.section<uint8_t>(sections.atlas, sections.owner);
  r.require(f.atlas.size() == uint64_t{stored} * kBrickSamples * bytes_per_sample(format),
            what + ": atlas of " + std::to_string(f.atlas.size()) + " bytes for " + std::to_string(stored) + " bricks");
  check_atlas_values(r, f, what);
  return f;
}

// A mesh's brick field, its coarse level at the brick corners (signed, finite).
BrickField read_bricks(const Reader& r, uint32_t mesh, const BrickFieldParams& params) {
  const std::string what = "mesh " + std::to_string(mesh) + " brick field";
  const BrickHeader h = r.single<BrickHeader>(kBrickHeader, mesh);
  BrickField f = read_field(r, what, h.origin, h.voxel, h.bricks, h.stored, h.build_ms, params.format, params.band,
                            {mesh, kBrickSlots, kBrickAtlas});
  f.coarse = r.section<float>(kBrickCoarse, mesh);
  r.require(f.coarse.size() == cell_product(h.bricks + 1u), what + ": coarse level count differs from its brick corners");
  r.require(std::all_of(f.coarse.begin(), f.coarse.end(), [](float v) { return std::isfinite(v); }),
            what + ": non-finite coarse value");
  return f;
}

// The scene's global field: its coarse level one lower bound per brick (finite, >= 0), and the
// per-brick instance lists as a prefix sum over the stored bricks whose every entry names an
// instance of the scene.
GlobalField read_global(const Reader& r, const GlobalFieldParams& params, uint32_t instance_count) {
  const std::string what = "global field";
  const GlobalHeader h = r.single<GlobalHeader>(kGlobalHeader, 0);
  GlobalField g;
  g.voxel_request = params.voxel;
  g.build_ms = h.build_ms;
  g.field = read_field(r, what, h.origin, h.voxel, h.bricks, h.stored, h.build_ms, params.format, params.band,
                       {0, kGlobalSlots, kGlobalAtlas});
  BrickField& f = g.field;
  f.coarse = r.section<float>(kGlobalCoarse, 0);
  f.coarse_at_centres = true;
  r.require(f.coarse.size() == cell_product(h.bricks), what + ": coarse level count differs from its bricks");
  r.require(std::all_of(f.coarse.begin(), f.coarse.end(), [](float v) { return std::isfinite(v) && v >= 0.0f; }),
            what + ": a coarse value is not finite or negative (it is a distance bound)");
  g.list_begin = r.section<uint32_t>(kGlobalListBegin, 0);
  g.list_instances = r.section<uint32_t>(kGlobalListInstances, 0);
  r.require(g.list_begin.size() == uint64_t{h.stored} + 1, what + ": list begin has " + std::to_string(g.list_begin.size()) +
                                                               " entries for " + std::to_string(h.stored) + " stored bricks");
  r.require(g.list_instances.size() == h.list_entries, what + ": " + std::to_string(g.list_instances.size()) +
                                                           " list instances, header says " + std::to_string(h.list_entries));
  r.require(g.list_begin.front() == 0 && std::is_sorted(g.list_begin.begin(), g.list_begin.end()) &&
                g.list_begin.back() == g.list_instances.size(),
            what + ": list begin is not a valid prefix sum of the brick lists");
  r.require(std::all_of(g.list_instances.begin(), g.list_instances.end(), [&](uint32_t k) { return k < instance_count; }),
            what + ": a brick list names an instance >= " + std::to_string(instance_count));
  return g;
}

template <class T>
bool all_finite(const std::vector<T>& v) {
  return std::all_of(v.begin(), v.end(), [](const T& x) { return finite(x); });
}

MeshDistanceGrid read_grid(const Reader& r, uint32_t mesh, uint32_t& triangles, uint32_t& vertices) {
  const std::string what = "mesh " + std::to_string(mesh) + " grid";
  const GridHeader h = r.single<GridHeader>(kGridHeader, mesh);
  r.require(finite(h.origin) && positive_finite(h.cell_size), what + ": origin or cell size not finite");
  r.require(h.dims.x && h.dims.y && h.dims.z && cell_product(h.dims) <= kMaxMeshCells, what + ": bad dimensions");
  r.require(h.triangles >= 1 && h.vertices >= 3, what + ": no triangles");
  MeshDistanceGrid g;
  g.origin = h.origin;
  g.cell_size = h.cell_size;
  g.dims = h.dims;
  g.build_ms = h.build_ms;
  g.cell_begin = r.section<uint32_t>(kCellBegin, mesh);
  g.cell_triangles = r.section<uint32_t>(kCellTriangles, mesh);
  r.require(g.cell_begin.size() == cell_product(h.dims) + 1, what + ": cell_begin has " + std::to_string(g.cell_begin.size()) +
                                                                  " entries for " + std::to_string(cell_product(h.dims)) + " cells");
  r.require(g.cell_begin.front() == 0 && std::is_sorted(g.cell_begin.begin(), g.cell_begin.end()) &&
                g.cell_begin.back() == g.cell_triangles.size(),
            what + ": cell_begin is not a valid prefix sum of the cell lists");
  r.require(std::all_of(g.cell_triangles.begin(), g.cell_triangles.end(), [&](uint32_t t) { return t < h.triangles; }),
            what + ": a cell lists a triangle index >= " + std::to_string(h.triangles));
  g.face_normals = r.section<glm::vec3>(kFaceNormals, mesh);
  g.edge_normals = r.section<glm::vec3>(kEdgeNormals, mesh);
  g.vertex_normals = r.section<glm::vec3>(kVertexNormals, mesh);
  r.require(g.face_normals.size() == h.triangles && g.edge_normals.size() == 3ull * h.triangles &&
                g.vertex_normals.size() == h.vertices,
            what + ": pseudo-normal counts do not match its triangles and vertices");
  r.require(all_finite(g.face_normals) && all_finite(g.edge_normals) && all_finite(g.vertex_normals),
            what + ": non-finite pseudo-normal");
  triangles = h.triangles;
  vertices = h.vertices;
  return g;
}

SceneHash read_hash(const Reader& r, const SceneHashParams& params, uint32_t instance_count) {
  const HashHeader h = r.single<HashHeader>(kHashHeader, 0);
  r.require(finite(h.origin) && h.cell_size == params.hash_cell, "scene hash: origin not finite or cell size differs from its parameter");
  r.require(h.dims.x && h.dims.y && h.dims.z && cell_product(h.dims) <= kMaxHashCells, "scene hash: bad dimensions");
  SceneHash hash;
  hash.origin = h.origin;
  hash.cell_size = h.cell_size;
  hash.dims = h.dims;
  hash.params = params;
  hash.build_ms = h.build_ms;
  hash.cell_root = r.section<uint32_t>(kCellRoot, 0);
  hash.nodes = r.section<OctreeNode>(kNodes, 0);
  hash.instance_lists = r.section<uint32_t>(kInstanceLists, 0);
  r.require(hash.cell_root.size() == cell_product(h.dims), "scene hash: cell_root count differs from its cells");
  const uint64_t node_count = hash.nodes.size();
  r.require(std::all_of(hash.cell_root.begin(), hash.cell_root.end(), [&](uint32_t n) { return n < node_count; }),
            "scene hash: a cell's root node is out of range");
  for (uint64_t i = 0; i < node_count; ++i) {
    const OctreeNode& n = hash.nodes[i];
    const std::string what = "octree node " + std::to_string(i);
    // Children strictly after their parent: every descent terminates.
    r.require(n.first_child == -1 || (n.first_child > 0 && static_cast<uint64_t>(n.first_child) > i &&
                                      static_cast<uint64_t>(n.first_child) + 8 <= node_count),
              what + ": child index out of range");
    r.require(n.depth <= params.octree_depth, what + ": deeper than the octree depth parameter");
    r.require(uint64_t{n.list_begin} + n.list_count <= hash.instance_lists.size(), what + ": instance list out of range");
  }
  r.require(std::all_of(hash.instance_lists.begin(), hash.instance_lists.end(), [&](uint32_t k) { return k < instance_count; }),
            "scene hash: an instance list names an instance >= " + std::to_string(instance_count));
  return hash;
}

}  // namespace

void reseal_sdf_cache(std::span<std::byte> bytes) {
  if (bytes.size() < sizeof(uint64_t)) return;
  const uint64_t sum = fnv1a64(bytes.first(bytes.size() - sizeof sum));
  std::memcpy(bytes.data() + bytes.size() - sizeof sum, &sum, sizeof sum);
}

std::vector<std::byte> encode_sdf_cache(const SdfCacheContents& c) {
  const uint32_t meshes = static_cast<uint32_t>(c.mesh_grids.size());
  FileHeader h{};
  std::memcpy(h.magic, kMagic, sizeof kMagic);
  h.version = kSdfCacheVersion;
  h.header_bytes = sizeof(FileHeader);
  h.scene_hash = c.scene_hash;
  h.mesh_count = meshes;
  h.instance_count = c.instance_count;
  h.mesh_cell_size = c.mesh_params.cell_size;
  h.cells_per_extent = c.mesh_params.cells_per_extent;
  h.margin_cells = c.mesh_params.margin_cells;
  h.mesh_rule = static_cast<uint32_t>(c.mesh_params.rule);
  h.subdivision = c.mesh_params.subdivision;
  h.hash_cell = c.hash_params.hash_cell;
  h.octree_depth = c.hash_params.octree_depth;
  h.octree_min_objects = c.hash_params.octree_min_objects;
  h.octree_min_size = c.hash_params.octree_min_size;
  h.lists = static_cast<uint32_t>(c.hash_params.lists);
  h.bricks = brick_word(c.brick_params);
  h.global = global_word(c.global_params);
  h.global_voxel = c.global_params ? c.global_params->voxel : 0.0f;

  std::vector<GridHeader> grid_headers;
  for (uint32_t m = 0; m < meshes; ++m) {
    const MeshDistanceGrid& g = c.mesh_grids[m];
    grid_headers.push_back({g.origin, g.cell_size, g.dims, c.mesh_triangles.at(m), c.mesh_vertices.at(m), 0, g.build_ms});
  }
  const HashHeader hash_header{c.hash.origin, c.hash.cell_size, c.hash.dims, 0, c.hash.build_ms};
  Writer w;
  for (uint32_t m = 0; m < meshes; ++m) {
    const MeshDistanceGrid& g = c.mesh_grids[m];
    w.add_one(kGridHeader, m, grid_headers[m]);
    w.add(kCellBegin, m, g.cell_begin);
    w.add(kCellTriangles, m, g.cell_triangles);
    w.add(kFaceNormals, m, g.face_normals);
    w.add(kEdgeNormals, m, g.edge_normals);
    w.add(kVertexNormals, m, g.vertex_normals);
  }
  w.add_one(kHashHeader, 0, hash_header);
  w.add(kCellRoot, 0, c.hash.cell_root);
  w.add(kNodes, 0, c.hash.nodes);
  w.add(kInstanceLists, 0, c.hash.instance_lists);
  std::vector<BrickHeader> brick_headers;
  if (c.brick_params) {
    for (uint32_t m = 0; m < meshes; ++m) {
      const BrickField& f = c.brick_fields.at(m);
      brick_headers.push_back({f.origin, f.voxel, f.bricks, static_cast<uint32_t>(f.stored_bricks()), f.build_ms});
    }
    for (uint32_t m = 0; m < meshes; ++m) {
      const BrickField& f = c.brick_fields[m];
      w.add_one(kBrickHeader, m, brick_headers[m]);
      w.add(kBrickSlots, m, f.indirection);
      w.add(kBrickAtlas, m, f.atlas);
      w.add(kBrickCoarse, m, f.coarse);
    }
  }
  const GlobalField& g = c.global_field;
  const GlobalHeader global_header{g.field.origin, g.field.voxel, g.field.bricks, static_cast<uint32_t>(g.field.stored_bricks()),
                                   static_cast<uint32_t>(g.list_instances.size()), 0, g.build_ms};
  if (c.global_params) {
    w.add_one(kGlobalHeader, 0, global_header);
    w.add(kGlobalSlots, 0, g.field.indirection);
    w.add(kGlobalAtlas, 0, g.field.atlas);
    w.add(kGlobalCoarse, 0, g.field.coarse);
    w.add(kGlobalListBegin, 0, g.list_begin);
    w.add(kGlobalListInstances, 0, g.list_instances);
  }
  return w.finish(h);
}

void check_sdf_cache_header(std::span<const std::byte> head, uint64_t file_bytes, const std::string& source) {
  check_header(head, file_bytes, source);
}

SdfCacheContents decode_sdf_cache(std::span<const std::byte> bytes, const std::string& source) {
  Reader r(bytes, source);
  const FileHeader h = r.header();
  SdfCacheContents c;
  c.version = h.version;
  c.scene_hash = h.scene_hash;
  c.instance_count = h.instance_count;
  c.file_bytes = h.file_bytes;
  check_params(r, h);
  c.mesh_params = {h.mesh_cell_size, h.cells_per_extent, h.margin_cells, static_cast<MeshGridRule>(h.mesh_rule), h.subdivision};
  c.hash_params = {h.hash_cell, h.octree_depth, h.octree_min_objects, h.octree_min_size, static_cast<ListRule>(h.lists)};
  for (uint32_t m = 0; m < h.mesh_count; ++m) {
    uint32_t triangles = 0, vertices = 0;
    c.mesh_grids.push_back(read_grid(r, m, triangles, vertices));
    c.mesh_triangles.push_back(triangles);
    c.mesh_vertices.push_back(vertices);
  }
  c.hash = read_hash(r, c.hash_params, h.instance_count);
  if (h.bricks != 0) {
    c.brick_params = brick_params_of(h.bricks);
    for (uint32_t m = 0; m < h.mesh_count; ++m) c.brick_fields.push_back(read_bricks(r, m, *c.brick_params));
  }
  if (h.global != 0) {
    c.global_params = global_params_of(h.global, h.global_voxel);
    c.global_field = read_global(r, *c.global_params, h.instance_count);
  }
  c.sections = r.describe();
  return c;
}

}  // namespace sdfbench::sdf
