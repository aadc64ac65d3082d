#include "renderers/sdf/cache/section_codec.h"

#include "renderers/sdf/scene_sdf.h"
#include "util/error.h"

namespace sdfbench::sdf {

// The optional structures' codecs, each defined in its structure's folder (declared here, as
// renderers/builtin_backends.cpp declares the backends, so that nothing of a backend's folder is
// included by renderers/sdf/).
const SectionCodec& brick_field_codec();   // sdf-bricks' brick fields (brick_field_codec.cpp)
const SectionCodec& global_field_codec();  // sdf-global's global field (global_field_codec.cpp)

// A new structure's codec goes here (after the structures its decode reads).
const std::vector<const SectionCodec*>& section_codecs() {
  static const std::vector<const SectionCodec*> codecs = {&mesh_grid_codec(), &scene_hash_codec(), &brick_field_codec(),
                                                          &global_field_codec()};
  return codecs;
}

const SectionCodec* codec_of_kind(uint32_t kind) {
  for (const SectionCodec* codec : section_codecs())
    if (codec->kind == kind) return codec;
  return nullptr;
}

const SectionCodec& codec_for(const StructureRequest& request) {
  const SectionCodec* codec = codec_of_kind(request.kind());
  if (!codec || !codec->optional)
    throw InternalError("no cache codec stores the structure requested with " + request.describe());
  return *codec;
}

bool SectionCodec::holds(const SceneSdf& sdf) const { return !optional || sdf.holds(kind); }

}  // namespace sdfbench::sdf
