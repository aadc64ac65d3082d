#pragma once
// Implicit objects (thesis 5.1, figure 6.5): primitives given by their distance formulas,
// combined by CSG union, intersection and subtraction; scenes/README.md documents the JSON form.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "scenes/aabb.h"
#include "scenes/transform.h"

namespace sdfbench {

// The values are the GLSL IMPLICIT_* kinds (renderers/shading/shading_types.glsl).
enum class ImplicitKind : uint32_t { Sphere, Box, Ellipsoid, Capsule, Torus, Plane, Union, Intersection, Subtraction };

inline bool is_operation(ImplicitKind kind) { return kind >= ImplicitKind::Union; }

struct ImplicitNode {
  ImplicitKind kind = ImplicitKind::Sphere;
  // Primitive parameters, laid out as renderers/shading/implicit_sdf.glsl reads them.
  glm::vec4 a{0.0f}, b{0.0f};
  Transform placement;  // the primitive's frame in the object (scale 1); unused by operations
};

// Limits the kernels rely on (IMPLICIT_MAX_NODES, IMPLICIT_STACK_SIZE).
inline constexpr uint32_t kImplicitMaxNodes = 64;
inline constexpr uint32_t kImplicitStackSize = 8;

struct ImplicitObject {
  std::vector<ImplicitNode> nodes;  // the CSG tree in postfix order: operands before their operation
  uint32_t material = 0;
  Transform transform;  // object to world, as an instance's
};

// Object-space box around the shape. Throws Error when the nodes are not a valid postfix tree
// within the limits above, or the shape is unbounded (a plane not cut down by an intersection)
// or provably empty (an intersection of disjoint bounds).
Aabb implicit_bounds(const std::vector<ImplicitNode>& nodes);

}  // namespace sdfbench
