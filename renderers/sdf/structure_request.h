#pragma once
// An optional structure a backend asks for besides the exact ones every SDF backend uses (mesh
// grids and scene hash), named by its build parameters: sdf-bricks asks for brick fields,
// sdf-global for the global field. build_scene_sdf and obtain_scene_sdf take a list of them, so
// a new structure adds its parameters to this variant (and a cache codec, cache/section_codec.h),
// not a parameter to their signatures.
#include <string>
#include <variant>
#include <vector>

#include "renderers/sdf_bricks/brick_field.h"
#include "renderers/sdf_global/global_field.h"

namespace sdfbench::sdf {

using StructureRequest = std::variant<BrickFieldParams, GlobalFieldParams>;
using StructureRequests = std::vector<StructureRequest>;

// The requested parameters as flags ("--voxels 16 --brick-band 3 --sdf-format f16").
inline std::string describe(const StructureRequest& request) {
  return std::visit([](const auto& params) { return describe(params); }, request);
}
// Throws Error naming the flag of a bad parameter.
inline void validate(const StructureRequest& request) {
  std::visit([](const auto& params) { validate(params); }, request);
}

}  // namespace sdfbench::sdf
