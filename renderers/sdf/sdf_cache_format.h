#pragma once
// The SDF cache file format, version 2 (little-endian, every section 8-byte aligned):
//
//   header          magic "SDFBCACH", format version, header size, file size, scene geometry
//                   hash, mesh/instance/section counts, every build parameter
//   section table   per section: kind, owner mesh, element size, offset, element count
//   sections        per mesh: grid header (origin, cell size, dims, triangle/vertex counts,
//                   build ms), cell_begin, cell_triangles, face/edge/vertex pseudo-normals;
//                   scene: hash header, cell_root, octree nodes, instance lists;
//                   only when the header's brick word is not 0 (sdf-bricks, issue 28), per mesh:
//                   brick header (origin, voxel, bricks, stored count, build ms), indirection,
//                   atlas (bytes in the word's format), coarse level;
//                   only when the header's global word is not 0 (sdf-global, issue 29), once:
//                   global header (origin, voxel, bricks, stored count, list entry count, build
//                   ms), indirection, atlas (in the word's format), coarse level (lower bounds,
//                   >= 0), list begin (stored + 1 prefix offsets), list instances
//   checksum        FNV-1a 64 of every byte before it
// (Version 2 added the global field's two header words, its voxel request as float bits among
// them; a version 1 file is refused as another version.)
//
// decode_sdf_cache trusts nothing: sizes, offsets, overlaps, counts, every index and every
// float are checked before a structure is returned, so a renderer can walk the result (and
// upload it to a GPU) without further checks. It needs no scene: `sdfbench inspect` uses it
// alone; load_sdf_cache (sdf_cache.h) adds the checks against a scene.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "renderers/sdf/brick_field.h"
#include "renderers/sdf/global_field.h"
#include "renderers/sdf/mesh_distance_grid.h"
#include "renderers/sdf/scene_hash.h"

namespace sdfbench::sdf {

inline constexpr uint32_t kSdfCacheVersion = 2;

// The largest cache sdfbench writes or reads: a reader refuses a bigger file by its size before
// allocating anything (the structures it would hold would not fit a renderer's memory either).
inline constexpr uint64_t kMaxSdfCacheBytes = 4ull << 30;

struct SdfCacheSection {
  std::string name;  // e.g. "mesh 0 cell_triangles"
  uint64_t offset = 0, count = 0, bytes = 0;
};

// Everything a cache holds. Mesh triangle and vertex counts make the grids checkable without
// the scene (triangle indices, pseudo-normal counts).
struct SdfCacheContents {
  uint32_t version = kSdfCacheVersion;
  uint64_t scene_hash = 0;
  uint32_t instance_count = 0;
  MeshGridParams mesh_params;
  SceneHashParams hash_params;
  std::vector<MeshDistanceGrid> mesh_grids;
  std::vector<uint32_t> mesh_triangles, mesh_vertices;  // per mesh
  SceneHash hash;
  std::optional<BrickFieldParams> brick_params;  // with a brick field per mesh, or none
  std::vector<BrickField> brick_fields;
  std::optional<GlobalFieldParams> global_params;  // with the scene's global field, or none
  GlobalField global_field;
  std::vector<SdfCacheSection> sections;  // filled by decode (for inspect)
  uint64_t file_bytes = 0;                // filled by decode
};

std::vector<std::byte> encode_sdf_cache(const SdfCacheContents& contents);

// Throws Error naming what is wrong (truncated, checksum mismatch, section out of bounds,
// index out of range, ...). `source` names the file in messages.
SdfCacheContents decode_sdf_cache(std::span<const std::byte> bytes, const std::string& source);

// What can be checked before a cache's body is read: its first kSdfCacheHeaderBytes bytes
// (magic, version, header size) and the size it declares against the file's `file_bytes`, so a
// file that is no cache of this version costs a few bytes to refuse, not its size. Throws the
// Error decode_sdf_cache would.
inline constexpr size_t kSdfCacheHeaderBytes = 96;
void check_sdf_cache_header(std::span<const std::byte> head, uint64_t file_bytes, const std::string& source);

// Recomputes the trailing checksum in place (the fuzz target uses it to get past the checksum
// and exercise the structural checks).
void reseal_sdf_cache(std::span<std::byte> bytes);

}  // namespace sdfbench::sdf
