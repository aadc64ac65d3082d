#pragma once
// One structure's part of the SDF cache file (format 3, sdf_cache_format.h): its sections, how
// it writes them and how it reads them back with every check, tagged in the section table with
// the codec's kind and its own version. The file decoder checks what every section shares
// (bounds, alignment, overlaps, element size, owner, no duplicates, none missing) and hands each
// codec its own; the codec checks their contents (counts, indices, floats) before a structure
// is returned. A new structure adds a codec in its own file and one line in section_codecs.cpp:
// no format-wide version bump (a file without its sections simply does not hold it).
#include <cstdint>
#include <string>
#include <vector>

#include "renderers/sdf/structure_request.h"

namespace sdfbench::sdf {

struct SceneSdf;
struct SdfCacheContents;
class SectionReader;
class SectionWriter;

struct SectionSpec {
  const char* name;        // "cell_begin"; inspect and messages prefix "mesh N " to a per-mesh one
  uint32_t element_bytes;  // the size of one element, checked against the table's
  bool per_mesh;           // one per mesh (owner = mesh index) rather than one per file
};

struct SectionCodec {
  uint32_t kind;     // the codec's tag in the section table; never reused for another structure
  const char* name;  // "brick fields": "holds no brick fields", inspect's list of structures
  // Bumped when its sections change: a file whose copy has another version is stale for this
  // structure (and only for it).
  uint32_t version;
  std::vector<SectionSpec> sections;  // the first holds the parameters it was built with
  // Optional structures are built when a StructureRequest asks for them (and added to a cache
  // that lacks them); the others (mesh grids, scene hash) are in every cache.
  bool optional = false;
  const char* the_name = "";  // "the global field", for "added the global field"

  bool (*held)(const SceneSdf& sdf) = nullptr;  // whether there is one to write (null: always)
  bool holds(const SceneSdf& sdf) const { return !held || held(sdf); }
  void (*encode)(const SdfCacheContents& contents, SectionWriter& out);
  // Fills its part of `contents` from its sections, all checked; throws Error otherwise.
  void (*decode)(const SectionReader& in, SdfCacheContents& contents);
  std::vector<std::string> (*summary)(const SdfCacheContents& contents);  // inspect's lines
  // Optional structures only: whether `request` asks for this structure, and what makes the held
  // one stale for it ("built with brick fields --voxels 16 ..., requested --voxels 32 ...",
  // empty when it serves the request).
  bool (*serves)(const StructureRequest& request) = nullptr;
  std::string (*differs)(const SceneSdf& held, const StructureRequest& request) = nullptr;
};

// Every codec, in the order their sections are written and decoded (a codec may read what an
// earlier one decoded: counts, parameters).
const std::vector<const SectionCodec*>& section_codecs();
const SectionCodec* codec_of_kind(uint32_t kind);  // null for a kind this sdfbench does not know
const SectionCodec& codec_for(const StructureRequest& request);

// The codecs (each in its own file under renderers/sdf/cache/).
const SectionCodec& mesh_grid_codec();
const SectionCodec& scene_hash_codec();
const SectionCodec& brick_field_codec();
const SectionCodec& global_field_codec();

}  // namespace sdfbench::sdf
