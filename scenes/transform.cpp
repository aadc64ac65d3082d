#include "scenes/transform.h"

#include <glm/gtc/matrix_transform.hpp>

#include "scenes/aabb.h"

namespace sdfbench {

glm::mat4 Transform::object_to_world() const {
  return glm::translate(glm::mat4(1.0f), translation) * glm::mat4_cast(rotation) *
         glm::scale(glm::mat4(1.0f), glm::vec3(scale));
}

glm::mat4 Transform::world_to_object() const {
  return glm::scale(glm::mat4(1.0f), glm::vec3(1.0f / scale)) * glm::mat4_cast(glm::conjugate(rotation)) *
         glm::translate(glm::mat4(1.0f), -translation);
}

Aabb transform_box(const Aabb& box, const glm::mat4& m) {
  Aabb world;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 p((corner & 1) ? box.max.x : box.min.x, (corner & 2) ? box.max.y : box.min.y,
                      (corner & 4) ? box.max.z : box.min.z);
    world.extend(glm::vec3(m * glm::vec4(p, 1.0f)));
  }
  return world;
}

}  // namespace sdfbench
