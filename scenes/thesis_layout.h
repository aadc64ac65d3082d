#pragma once
// The thesis benchmark scenes: `thesis:<mesh>[@<triangles>]:<count>[:seed]` (rules in
// scenes/README.md); `@<triangles>` resizes the mesh (scenes/sized_mesh.h).
#include <cstdint>
#include <string>

#include "scenes/scene.h"

namespace sdfbench {

struct ThesisLayoutSpec {
  std::string mesh;     // bunny, teapot, monkey or sphere
  uint32_t count = 1;   // instances
  uint64_t seed = 1;
  uint32_t triangles = 0;  // > 0: the mesh resized to about this many triangles
};

// Parses "thesis:bunny:100[:7]" or "thesis:bunny@64000:100"; throws Error on any malformed part.
ThesisLayoutSpec parse_thesis_spec(const std::string& spec);

Scene make_thesis_scene(const ThesisLayoutSpec& spec);

}  // namespace sdfbench
