#pragma once
// The thesis benchmark scenes: `thesis:<mesh>:<count>[:seed]` (rules in scenes/README.md).
#include <cstdint>
#include <string>

#include "scenes/scene.h"

namespace sdfbench {

struct ThesisLayoutSpec {
  std::string mesh;     // bunny, teapot, monkey or sphere
  uint32_t count = 1;   // instances
  uint64_t seed = 1;
};

// Parses "thesis:bunny:100[:7]"; throws Error on any malformed part.
ThesisLayoutSpec parse_thesis_spec(const std::string& spec);

Scene make_thesis_scene(const ThesisLayoutSpec& spec);

}  // namespace sdfbench
