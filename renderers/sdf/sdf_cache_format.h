#pragma once
// The SDF cache file format, version 3 (little-endian, every section 8-byte aligned):
//
//   header          magic "SDFBCACH", format version, header size, file size, scene geometry
//                   hash, mesh/instance/section counts
//   section table   per section: codec kind, codec version, section index within the codec,
//                   owner mesh, element size, offset, element count
//   sections        per structure, written by its codec (cache/section_codec.h): first its build
//                   parameters, then its payload; mesh grids and the scene hash in every file,
//                   brick fields (sdf-bricks) and the global field (sdf-global) when built
//   checksum        FNV-1a 64 of every byte before it
// A structure's layout is versioned by its codec, not by the file: a file whose copy of a
// structure has another codec version (or that holds a structure this sdfbench does not know)
// is read without it, and the structure is stale for whoever asks for it. (Version 3 moved the
// build parameters from the header into each structure's sections; a version 1 or 2 file is
// refused as another version.)
//
// decode_sdf_cache trusts nothing: sizes, offsets, overlaps, counts, every index and every
// float are checked before a structure is returned, so a renderer can walk the result (and
// upload it to a GPU) without further checks. It needs no scene: `sdfbench inspect` uses it
// alone; load_sdf_cache (sdf_cache.h) adds the checks against a scene.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "renderers/sdf/mesh_distance_grid.h"
#include "renderers/sdf/scene_hash.h"

namespace sdfbench::sdf {

inline constexpr uint32_t kSdfCacheVersion = 3;

// The largest cache sdfbench writes or reads: a reader refuses a bigger file by its size before
// allocating anything (the structures it would hold would not fit a renderer's memory either).
inline constexpr uint64_t kMaxSdfCacheBytes = 4ull << 30;

struct SdfCacheSection {
  std::string name;  // e.g. "mesh 0 cell_triangles"
  uint64_t offset = 0, count = 0, bytes = 0;
};

// A structure the file holds, as decode found it.
struct StoredStructure {
  uint32_t kind = 0, version = 0;
  std::string name;   // the codec's, or "kind N" for one this sdfbench does not know
  bool read = false;  // false: another codec version, or an unknown kind (not decoded)
};

// Everything a cache holds. Mesh triangle and vertex counts make the grids checkable without
// the scene (triangle indices, pseudo-normal counts).
struct SdfCacheContents {
  uint32_t version = kSdfCacheVersion;
  uint64_t scene_hash = 0;
  uint32_t instance_count = 0;
  MeshGridParams mesh_params;
  std::vector<uint32_t> mesh_triangles, mesh_vertices;  // per mesh
  // The mesh grids, the scene hash (its parameters in hash.params) and the optional structures
  // held (brick fields, global field); world_to_object is left empty (it needs the scene).
  SceneSdf sdf;
  std::vector<StoredStructure> structures;  // filled by decode (for inspect and stale messages)
  std::vector<SdfCacheSection> sections;    // filled by decode (for inspect)
  uint64_t file_bytes = 0;                  // filled by decode
};

std::vector<std::byte> encode_sdf_cache(const SdfCacheContents& contents);

// Throws Error naming what is wrong (truncated, checksum mismatch, section out of bounds,
// index out of range, ...). `source` names the file in messages.
SdfCacheContents decode_sdf_cache(std::span<const std::byte> bytes, const std::string& source);

// What can be checked before a cache's body is read: its first kSdfCacheHeaderBytes bytes
// (magic, version, header size) and the size it declares against the file's `file_bytes`, so a
// file that is no cache of this version costs a few bytes to refuse, not its size. Throws the
// Error decode_sdf_cache would.
inline constexpr size_t kSdfCacheHeaderBytes = 48;
void check_sdf_cache_header(std::span<const std::byte> head, uint64_t file_bytes, const std::string& source);

// Recomputes the trailing checksum in place (the fuzz target uses it to get past the checksum
// and exercise the structural checks).
void reseal_sdf_cache(std::span<std::byte> bytes);

}  // namespace sdfbench::sdf
