#pragma once
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "scenes/aabb.h"

namespace sdfbench {

// Rotation, uniform scale and translation only: distances scale back exactly (SDF backends).
struct Transform {
  glm::vec3 translation{0.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
  float scale = 1.0f;

  glm::mat4 object_to_world() const;
  glm::mat4 world_to_object() const;
};

// The box around `box` transformed by `m` (an affine map): its 8 corners' bounds.
Aabb transform_box(const Aabb& box, const glm::mat4& m);

}  // namespace sdfbench
