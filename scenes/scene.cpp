#include "scenes/scene.h"

#include <glm/gtc/matrix_transform.hpp>

namespace sdfbench {

glm::mat4 Transform::object_to_world() const {
  return glm::translate(glm::mat4(1.0f), translation) * glm::mat4_cast(rotation) *
         glm::scale(glm::mat4(1.0f), glm::vec3(scale));
}

glm::mat4 Transform::world_to_object() const {
  return glm::scale(glm::mat4(1.0f), glm::vec3(1.0f / scale)) * glm::mat4_cast(glm::conjugate(rotation)) *
         glm::translate(glm::mat4(1.0f), -translation);
}

Aabb Scene::world_bounds(const Instance& instance) const {
  const Aabb& local = meshes[instance.mesh].bounds;
  const glm::mat4 m = instance.transform.object_to_world();
  Aabb world;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 p((corner & 1) ? local.max.x : local.min.x, (corner & 2) ? local.max.y : local.min.y,
                      (corner & 4) ? local.max.z : local.min.z);
    world.extend(glm::vec3(m * glm::vec4(p, 1.0f)));
  }
  return world;
}

Aabb Scene::instance_bounds() const {
  Aabb bounds;
  for (const Instance& instance : instances) bounds.extend(world_bounds(instance));
  return bounds;
}

size_t Scene::triangle_count() const {
  size_t count = 0;
  for (const Instance& instance : instances) count += meshes[instance.mesh].triangle_count();
  return count;
}

}  // namespace sdfbench
