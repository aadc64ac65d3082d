#pragma once
// The scene distance as the sphere tracers evaluate it, sdf-cpu (SphereTracer) and the Vulkan
// kernels (sdf_scene_distance.glsl) alike: scene_distance() with two shortcuts that change no
// distance, only the work. A listed instance whose box is no nearer than the best distance so
// far is skipped, and mesh-grid cells are walked through MeshTraceLists (nearest triangles first,
// bounding-sphere skip). Both tracers take the shortcuts' data from here, so that they do, and
// count, the same work.
#include <vector>

#include "renderers/sdf/crossing_lists.h"
#include "renderers/sdf/scene_hash.h"

namespace sdfbench::sdf {

struct TraceCulling {
  std::vector<MeshTraceLists> meshes;
  std::vector<MeshCrossingLists> crossings;  // per mesh: the exact hits' lists
  std::vector<Aabb> instance_boxes;  // world box around each instance's mesh bounds, padded for rounding
};
TraceCulling make_trace_culling(const Scene& scene, const SceneSdf& sdf);

// scene_distance() through the shortcuts, with the work counts of SceneDistance filled.
SceneDistance traced_scene_distance(const SceneSdf& sdf, const Scene& scene, const TraceCulling& culling, const glm::vec3& p);

}  // namespace sdfbench::sdf
