#include "renderers/sdf/traced_distance.h"

#include <limits>

#include "scenes/transform.h"

namespace sdfbench::sdf {
namespace {

constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();

float box_distance(const Aabb& box, const glm::vec3& p) {
  return glm::length(glm::max(glm::max(box.min - p, p - box.max), glm::vec3(0.0f)));
}

// World box around the transformed mesh-bounds box: no farther from any point than the
// instance's surface or than the bound the mesh grid returns outside its box (the distance to
// that rotated box), so a distance to it that cannot beat the best so far safely skips the instance.
Aabb enclosing_box(const Aabb& bounds, const glm::mat4& object_to_world) {
  const Aabb box = transform_box(bounds, object_to_world);
  const glm::vec3 pad(1e-5f * glm::length(box.extent()));  // float rounding stays on the safe side
  return Aabb{box.min - pad, box.max + pad};
}

}  // namespace

TraceCulling make_trace_culling(const Scene& scene, const SceneSdf& sdf) {
  TraceCulling culling;
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    culling.meshes.push_back(make_trace_lists(sdf.mesh_grids[m], scene.meshes[m]));
    culling.crossings.push_back(make_crossing_lists(sdf.mesh_grids[m], scene.meshes[m]));
  }
  for (const Instance& instance : scene.instances)
    culling.instance_boxes.push_back(enclosing_box(scene.meshes[instance.mesh].bounds, instance.transform.object_to_world()));
  return culling;
}

SceneDistance traced_scene_distance(const SceneSdf& sdf, const Scene& scene, const TraceCulling& culling, const glm::vec3& p) {
  const SceneHash& hash = sdf.hash;
  const float outside = box_distance(Aabb{hash.origin, hash.origin + glm::vec3(hash.dims) * hash.cell_size}, p);
  if (outside > 0.0f) return {outside, kNone, kNone, 0};
  const OctreeNode& leaf = leaf_at(hash, p);
  SceneDistance best{std::numeric_limits<float>::infinity(), kNone, kNone, 0};
  for (uint32_t k = 0; k < leaf.list_count; ++k) {
    const uint32_t i = hash.instance_lists[leaf.list_begin + k];
    ++best.box_tests;
    if (box_distance(culling.instance_boxes[i], p) >= best.distance) continue;
    ++best.evaluations;
    const Instance& instance = scene.instances[i];
    const glm::vec3 local(sdf.world_to_object[i] * glm::vec4(p, 1.0f));
    uint32_t triangle = kNone;
    const float d = traced_grid_distance(sdf.mesh_grids[instance.mesh], scene.meshes[instance.mesh],
                                         culling.meshes[instance.mesh], local, triangle, best.triangle_evaluations) *
                    instance.transform.scale;
    if (d < best.distance) {
      best.distance = d;
      best.instance = i;
      best.triangle = triangle;
    }
  }
  return best;
}

}  // namespace sdfbench::sdf
