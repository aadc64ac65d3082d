#pragma once
// A generated architectural interior, `atrium[:<detail>[:<camera>]]` (scenes/README.md, "The
// atrium"): the scene type the thesis' object clouds are not — long-range occlusion (walls,
// piers, a gallery), large thin polygons (walls, gallery slabs, panes), a marble floor, many materials (stone, marble
// checker, bronze, a mirror wall, glass panes), and a few hundred thousand triangles in shared,
// instanced meshes (columns, arches). Deterministic from its parameters; fixed cameras.
#include <cstdint>
#include <string>

#include "scenes/scene.h"

namespace sdfbench {

struct AtriumSpec {
  uint32_t detail = 4;  // 1..8: tessellation of the columns and arches (triangles grow as detail^2)
  uint32_t camera = 0;  // 0: the nave from the entrance, 1: down the nave from above, 2: along an aisle
};
inline constexpr uint32_t kAtriumMaxDetail = 8, kAtriumCameras = 3;

// Parses "atrium", "atrium:6" or "atrium:6:2"; throws Error naming the part.
AtriumSpec parse_atrium_spec(const std::string& spec);
Scene make_atrium_scene(const AtriumSpec& spec);

}  // namespace sdfbench
