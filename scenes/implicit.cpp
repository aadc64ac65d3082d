#include "scenes/implicit.h"

#include <cmath>
#include <limits>

#include "util/error.h"


namespace sdfbench {
namespace {

// The primitive's box in the object frame; a plane's half-space is all of space.
Aabb primitive_bounds(const ImplicitNode& n) {
  const float inf = std::numeric_limits<float>::infinity();
  const glm::vec3 a(n.a), b(n.b);
  Aabb local;
  switch (n.kind) {
    case ImplicitKind::Sphere:
      return Aabb{n.placement.translation - n.a.x, n.placement.translation + n.a.x};
    case ImplicitKind::Box:
    case ImplicitKind::Ellipsoid:
      local = Aabb{-a, a};
      break;
    case ImplicitKind::Capsule:
      local = Aabb{glm::min(a, b) - n.a.w, glm::max(a, b) + n.a.w};
      break;
    case ImplicitKind::Torus: {
      const glm::vec3 r(n.a.x + n.a.y, n.a.y, n.a.x + n.a.y);
      local = Aabb{-r, r};
      break;
    }
    default:
      return Aabb{glm::vec3(-inf), glm::vec3(inf)};
  }
  return transform_box(local, n.placement.object_to_world());
}

}  // namespace

Aabb implicit_bounds(const std::vector<ImplicitNode>& nodes) {
  if (nodes.empty() || nodes.size() > kImplicitMaxNodes)
    throw Error("an implicit shape needs 1 to " + std::to_string(kImplicitMaxNodes) + " nodes, not " +
                std::to_string(nodes.size()));
  std::vector<Aabb> stack;  // postfix evaluation of the bounds, as the kernels evaluate distances
  for (const ImplicitNode& n : nodes) {
    if (!is_operation(n.kind)) {
      stack.push_back(primitive_bounds(n));
      if (stack.size() > kImplicitStackSize)
        throw Error("the shape needs an evaluation stack deeper than " + std::to_string(kImplicitStackSize) +
                    "; nest operations less deeply (list more children in one operation instead)");
      continue;
    }
    if (stack.size() < 2) throw InternalError("malformed implicit shape (an operation without two operands)");
    const Aabb b = stack.back();
    stack.pop_back();
    Aabb& a = stack.back();
    if (n.kind == ImplicitKind::Union) {
      a.extend(b);
    } else if (n.kind == ImplicitKind::Intersection) {
      a = Aabb{glm::max(a.min, b.min), glm::min(a.max, b.max)};
    }  // subtraction: inside the first operand
  }
  if (stack.size() != 1) throw InternalError("malformed implicit shape (operands left over)");
  const Aabb box = stack.back();
  for (int axis = 0; axis < 3; ++axis) {
    if (!std::isfinite(box.min[axis]) || !std::isfinite(box.max[axis]))
      throw Error("the shape is unbounded: a plane must be intersected with a bounded shape (or subtracted from one)");
    if (box.min[axis] > box.max[axis])
      throw Error("the shape is empty: the operands of an intersection do not overlap");
  }
  return box;
}

}  // namespace sdfbench
