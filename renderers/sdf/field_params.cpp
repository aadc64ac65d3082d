// The sampled fields' parameters in words (brick_field.h, global_field.h): apart from their
// builders, so that the cache codecs (and the cache fuzz target, which compiles no builder) can
// name them in messages.
#include <sstream>

#include "renderers/sdf_bricks/brick_field.h"
#include "renderers/sdf_global/global_field.h"

namespace sdfbench::sdf {

std::string to_string(SdfFormat format) {
  switch (format) {
    case SdfFormat::f32: return "f32";
    case SdfFormat::f16: return "f16";
    case SdfFormat::u8: return "u8";
  }
  return "?";
}

std::string describe(const BrickFieldParams& params) {
  return "--voxels " + std::to_string(params.voxels) + " --brick-band " + std::to_string(params.band) + " --sdf-format " +
         to_string(params.format);
}

std::string describe(const GlobalFieldParams& params) {
  std::ostringstream out;
  out << "--global-voxel ";
  if (params.voxel > 0.0f) out << params.voxel; else out << "auto";
  out << " --brick-band " << params.band << " --sdf-format " << to_string(params.format);
  return out.str();
}

}  // namespace sdfbench::sdf
