#include "scenes/scene.h"

namespace sdfbench {

Aabb Scene::world_bounds(const Instance& instance) const {
  return transform_box(meshes[instance.mesh].bounds, instance.transform.object_to_world());
}

Aabb Scene::world_bounds(const ImplicitObject& object) const {
  return transform_box(implicit_bounds(object.nodes), object.transform.object_to_world());
}

Aabb Scene::instance_bounds() const {
  Aabb bounds;
  for (const Instance& instance : instances) bounds.extend(world_bounds(instance));
  return bounds;
}

Aabb Scene::bounds() const {
  Aabb bounds = instance_bounds();
  for (const ImplicitObject& object : implicits) bounds.extend(world_bounds(object));
  return bounds;
}

size_t Scene::triangle_count() const {
  size_t count = 0;
  for (const Instance& instance : instances) count += meshes[instance.mesh].triangle_count();
  return count;
}

}  // namespace sdfbench
