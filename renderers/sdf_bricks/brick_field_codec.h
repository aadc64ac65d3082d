#pragma once
// What a mesh's brick field and the global field share in the cache: the brick format's header
// values, indirection and atlas, read and checked the same way by both codecs (read_field is
// defined in brick_field_codec.cpp, the brick format's codec).
#include <cstdint>
#include <string>

#include <glm/glm.hpp>

#include "renderers/sdf/cache/section_reader.h"
#include "renderers/sdf_bricks/brick_field.h"

namespace sdfbench::sdf {

// Enum values as stored (SdfFormat), checked before they become enums.
inline bool valid_format(uint32_t format) { return format <= static_cast<uint32_t>(SdfFormat::u8); }

struct FieldHeaderValues {
  glm::vec3 origin;
  float voxel;
  glm::uvec3 bricks;
  uint32_t stored;
  double build_ms;
};
struct FieldSectionIndices {
  uint32_t owner, indirection, atlas;
};

// Every index in range, every count what the header implies, values within the band (a NaN
// would stall no march but mislead every bound); band and quantization are recomputed from the
// parameters, never taken from the file. The coarse level is the caller's (it differs).
BrickField read_field(const SectionReader& in, const std::string& what, const FieldHeaderValues& header, SdfFormat format,
                      uint32_t band, FieldSectionIndices sections);

}  // namespace sdfbench::sdf
