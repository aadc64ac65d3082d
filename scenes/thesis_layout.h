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

// Shared with the other generators (overlap_layout.h).
inline constexpr float kThesisBaseRadius = 4.0f;  // bounding-sphere radius of an object at scale factor 1
inline constexpr float kThesisMinScale = 0.75f, kThesisMaxScale = 1.25f;
inline constexpr uint32_t kMaxThesisCount = 100000;
// A non-negative integer part of `spec`; throws Error naming `what` (and the type's limit).
uint64_t parse_spec_integer(const std::string& text, const std::string& spec, const char* what);
// Diffuse, reflective and refractive variants of six albedos, then the floor's checker.
void add_thesis_materials(Scene& scene);
// The floor, the sun and the camera of the thesis' 140 x 100 x 140 region scaled by `scale`.
void add_thesis_stage(Scene& scene, float scale);

}  // namespace sdfbench
