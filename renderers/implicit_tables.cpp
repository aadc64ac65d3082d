#include "renderers/implicit_tables.h"

namespace sdfbench {
namespace {

static_assert(static_cast<uint32_t>(ImplicitKind::Sphere) == IMPLICIT_SPHERE &&
              static_cast<uint32_t>(ImplicitKind::Plane) == IMPLICIT_PLANE &&
              static_cast<uint32_t>(ImplicitKind::Union) == IMPLICIT_UNION &&
              static_cast<uint32_t>(ImplicitKind::Subtraction) == IMPLICIT_SUBTRACTION);
static_assert(kImplicitMaxNodes == IMPLICIT_MAX_NODES && kImplicitStackSize == IMPLICIT_STACK_SIZE);

// Row r of an affine matrix (glm is column-major).
glm::vec4 row(const glm::mat4& m, int r) { return glm::vec4(m[0][r], m[1][r], m[2][r], m[3][r]); }

}  // namespace

ImplicitTables make_implicit_tables(const Scene& scene) {
  ImplicitTables tables;
  for (size_t k = 0; k < scene.implicits.size(); ++k) {
    const ImplicitObject& object = scene.implicits[k];
    const Aabb box = implicit_bounds(object.nodes);
    const float size = glm::length(box.extent());
    // A margin keeps flat faces off the box's faces, where marching starts.
    const glm::vec3 pad(1e-3f * size);
    const glm::mat4 to_object = object.transform.world_to_object();
    const glm::mat4 to_world = object.transform.object_to_world();
    shading::GpuImplicitObject g{};
    g.bounds_min = glm::vec4(box.min - pad, 1e-4f * size);  // w: normal step, small against the shape
    g.bounds_max = glm::vec4(box.max + pad, object.transform.scale);
    g.to_object0 = row(to_object, 0);
    g.to_object1 = row(to_object, 1);
    g.to_object2 = row(to_object, 2);
    g.to_world0 = glm::vec4(glm::vec3(row(to_world, 0)), 0.0f);
    g.to_world1 = glm::vec4(glm::vec3(row(to_world, 1)), 0.0f);
    g.to_world2 = glm::vec4(glm::vec3(row(to_world, 2)), 0.0f);
    g.info = glm::uvec4(tables.nodes.size(), object.nodes.size(), object.material, scene.instances.size() + k);
    tables.objects.push_back(g);
    for (const ImplicitNode& n : object.nodes) {
      const glm::mat4 to_local = n.placement.world_to_object();
      shading::GpuImplicitNode gn{};
      gn.info = glm::uvec4(static_cast<uint32_t>(n.kind), 0u, 0u, 0u);
      gn.a = n.a;
      gn.b = n.b;
      gn.to_local0 = row(to_local, 0);
      gn.to_local1 = row(to_local, 1);
      gn.to_local2 = row(to_local, 2);
      tables.nodes.push_back(gn);
    }
  }
  return tables;
}

}  // namespace sdfbench
