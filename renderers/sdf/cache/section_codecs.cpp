#include "renderers/sdf/cache/section_codec.h"


#include "util/error.h"

namespace sdfbench::sdf {

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
  for (const SectionCodec* codec : section_codecs())
    if (codec->optional && codec->serves(request)) return *codec;
  throw Error("internal: no cache codec stores the structure requested with " + describe(request));
}

}  // namespace sdfbench::sdf
