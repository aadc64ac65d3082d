#pragma once
// One structure's part of the SDF cache file (format 3, sdf_cache_format.h): its sections, how
// it writes them and how it reads them back with every check, tagged in the section table with
// the codec's kind and its own version. The file decoder checks what every section shares
// (bounds, alignment, overlaps, element size, owner, no duplicates, none missing) and hands each
// codec its own; the codec checks their contents (counts, indices, floats) before a structure
// is returned. A new structure adds a codec in its own folder and one line in section_codecs.cpp:
// no format-wide version bump (a file without its sections simply does not hold it).
#include <cstdint>
#include <string>
#include <vector>

#include "renderers/sdf/structure_request.h"  // only to name a request in codec_for's message

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
  // The codec's tag in the section table, never reused for another structure; an optional
  // structure's key in SceneSdf::optional (its entry type's kKind).
  uint32_t kind;
  const char* name;  // "brick fields": "holds no brick fields", inspect's list of structures
  // Bumped when its sections change: a file whose copy has another version is stale for this
  // structure (and only for it).
  uint32_t version;
  std::vector<SectionSpec> sections;  // the first holds the parameters it was built with
  // Optional structures are built when a StructureRequest asks for them (and added to a cache
  // that lacks them); the others (mesh grids, scene hash) are in every cache. The request, not
  // the codec, says which parameters a held one must have (StructureRequest::differs).
  bool optional = false;
  const char* the_name = "";  // "the global field", for "added the global field"

  // Whether `sdf` has one to write: the exact structures always, an optional one when held.
  bool holds(const SceneSdf& sdf) const;
  void (*encode)(const SdfCacheContents& contents, SectionWriter& out);
  // Fills its part of `contents` from its sections, all checked; throws Error otherwise.
  void (*decode)(const SectionReader& in, SdfCacheContents& contents);
  std::vector<std::string> (*summary)(const SdfCacheContents& contents);  // inspect's lines
};

// Every codec, in the order their sections are written and decoded (a codec may read what an
// earlier one decoded: counts, parameters).
const std::vector<const SectionCodec*>& section_codecs();
const SectionCodec* codec_of_kind(uint32_t kind);  // null for a kind this sdfbench does not know
const SectionCodec& codec_for(const StructureRequest& request);  // the one of request.kind()

// The exact structures' codecs (under renderers/sdf/cache/); an optional structure's codec is
// in its own folder, declared where section_codecs.cpp lists it.
const SectionCodec& mesh_grid_codec();
const SectionCodec& scene_hash_codec();

}  // namespace sdfbench::sdf
