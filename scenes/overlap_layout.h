#pragma once
// Scenes of overlapping instances (issue 37): `overlap:<mesh>:<count>:<k>[:seed]` keeps the
// thesis' objects (its meshes, sizes, materials, floor and light) and shrinks the region they are
// scattered in until the instances' boxes cover each point of their union about k times over
// (k = 1: as dense as touching; the thesis layout itself never overlaps). The overlap a scene
// really has is measured (measured_overlap) and written in every CSV row.
#include <cstdint>
#include <string>

#include "scenes/scene.h"

namespace sdfbench {

struct OverlapLayoutSpec {
  std::string mesh;     // bunny, teapot, monkey or sphere
  uint32_t count = 1;   // instances
  double overlap = 1;   // k: the boxes' summed volume over the region's, 1 .. kMaxOverlap
  uint64_t seed = 1;
};

inline constexpr double kMaxOverlap = 64;

// Parses "overlap:bunny:1000:8[:seed]"; throws Error naming the part that is malformed.
OverlapLayoutSpec parse_overlap_spec(const std::string& spec);
Scene make_overlap_scene(const OverlapLayoutSpec& spec);

// The mean number of instance boxes (world AABBs) that contain a point of their union, estimated
// from `samples` points (deterministic): each point is drawn in a box chosen by its volume, which
// samples the union with density proportional to the count c, so the mean is 1 / E[1/c]. 0 for a
// scene without instances.
double measured_overlap(const Scene& scene, uint32_t samples = 4096);

}  // namespace sdfbench
