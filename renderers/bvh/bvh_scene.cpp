#include "renderers/bvh/bvh_scene.h"

#include <algorithm>
#include <cmath>
#include <queue>
#include <string>

#include "scenes/transform.h"
#include "util/error.h"

namespace sdfbench {
namespace {

// What the flat tree keeps per triangle: 3 vertex and 3 normal texels (16 bytes each), its
// origin (16 bytes), and about 32 bytes of nodes and references.
constexpr uint64_t kFlatBytesPerTriangle = 3 * 16 + 3 * 16 + 16 + 32;

float area(const Aabb& box) {
  if (box.empty()) return 0.0f;
  const glm::vec3 e = box.extent();
  return 2.0f * (e.x * e.y + e.y * e.z + e.z * e.x);
}

// Opens entries into their children, largest world area first, while the top level has room
// (budget entries). An entry names an inner node; a node with a leaf child stays whole (the
// top level refers to nodes, never to leaves).
void rebraid(const Scene& scene, const std::vector<BvhTree>& meshes, size_t budget, std::vector<BvhEntry>& entries,
             std::vector<Aabb>& boxes) {
  struct Open {
    float area;
    size_t entry;
    bool operator<(const Open& o) const { return area < o.area || (area == o.area && entry > o.entry); }
  };
  std::priority_queue<Open> largest;
  for (size_t i = 0; i < entries.size(); ++i) largest.push({area(boxes[i]), i});
  while (!largest.empty()) {
    const size_t e = largest.top().entry;
    largest.pop();
    const BvhEntry entry = entries[e];
    const BvhTree& tree = meshes[scene.instances[entry.instance].mesh];
    const BvhTreeNode& node = tree.nodes[entry.node];
    const bool all_inner = std::none_of(node.children.begin(), node.children.begin() + node.child_count,
                                        [](const BvhChild& c) { return c.leaf(); });
    if (!all_inner || node.child_count < 2 || entries.size() + node.child_count - 1 > budget) continue;
    const glm::mat4 to_world = scene.instances[entry.instance].transform.object_to_world();
    for (uint32_t k = 0; k < node.child_count; ++k) {
      const BvhEntry child{entry.instance, node.children[k].index};
      const Aabb box = transform_box(node.children[k].box, to_world);
      const size_t at = k == 0 ? e : entries.size();
      if (k == 0) {
        entries[e] = child;
        boxes[e] = box;
      } else {
        entries.push_back(child);
        boxes.push_back(box);
      }
      largest.push({area(box), at});
    }
  }
}

BvhScene build_flat(RTCDevice device, const Scene& scene, const BvhSceneParams& params) {
  const uint64_t bytes = flat_bvh_bytes(scene);
  if (bytes > params.max_bytes)
    throw Error("bvh: --bvh-top flat needs about " + std::to_string(bytes >> 20) + " MiB for the " +
                std::to_string(scene.triangle_count()) + " world-space triangles of " + std::to_string(scene.instances.size()) +
                " instances, more than --max-structure-mb " + std::to_string(params.max_bytes >> 20) +
                " allows; raise --max-structure-mb or use --bvh-top instanced or rebraided");
  BvhScene out;
  out.top_kind = BvhTop::Flat;
  out.flat_world.instances.push_back(Instance{});
  Mesh& world = out.flat_world.meshes.emplace_back();
  world.name = "world";
  const size_t triangles = scene.triangle_count();
  world.positions.reserve(3 * triangles);
  world.normals.reserve(3 * triangles);
  world.triangles.reserve(triangles);
  out.flat_triangles.reserve(triangles);
  for (uint32_t i = 0; i < scene.instances.size(); ++i) {
    const Instance& instance = scene.instances[i];
    const Mesh& mesh = scene.meshes[instance.mesh];
    const glm::mat4 m = instance.transform.object_to_world();
    const glm::mat3 normal_to_world(m);  // as every backend turns normals (uniform scale)
    for (uint32_t t = 0; t < mesh.triangles.size(); ++t) {
      const uint32_t first = static_cast<uint32_t>(world.positions.size());
      for (int k = 0; k < 3; ++k) {
        const uint32_t v = mesh.triangles[t][k];
        world.positions.push_back(glm::vec3(m * glm::vec4(mesh.positions[v], 1.0f)));
        world.normals.push_back(normal_to_world * mesh.normals[v]);
        world.bounds.extend(world.positions.back());
      }
      world.triangles.push_back({first, first + 1, first + 2});
      out.flat_triangles.push_back({i, t, instance.material});
    }
  }
  out.top = build_mesh_bvh(device, world, bvh_mesh_build(params.width));
  return out;
}

}  // namespace

// Measured on lavapipe (thesis:bunny:1000, primary, 640x360, binary nodes): leaves of 1, 2 or 4
// triangles trace alike (1.80, 1.78, 1.79 Mrays/s), 8 slower (1.68); spatial splits (HIGH) beat
// binned SAH (MEDIUM) by 7 % (1.79 vs 1.67). One entry a top-level leaf.
BvhBuildParams bvh_mesh_build(uint32_t width) { return {RTC_BUILD_QUALITY_HIGH, width, 4}; }
BvhBuildParams bvh_top_build(uint32_t width) { return {RTC_BUILD_QUALITY_MEDIUM, width, 1}; }

uint64_t flat_bvh_bytes(const Scene& scene) { return static_cast<uint64_t>(scene.triangle_count()) * kFlatBytesPerTriangle; }

BvhScene build_bvh_scene(RTCDevice device, const Scene& scene, const BvhSceneParams& params) {
  if (params.top == BvhTop::Flat) return build_flat(device, scene, params);
  BvhScene out;
  out.top_kind = params.top;
  for (const Mesh& mesh : scene.meshes) out.meshes.push_back(build_mesh_bvh(device, mesh, bvh_mesh_build(params.width)));
  std::vector<Aabb> boxes;
  for (uint32_t i = 0; i < scene.instances.size(); ++i) {
    out.entries.push_back({i, 0});
    boxes.push_back(scene.world_bounds(scene.instances[i]));
  }
  if (params.top == BvhTop::Rebraided) {
    const double budget = std::max(1.0, params.rebraid) * static_cast<double>(scene.instances.size());
    rebraid(scene, out.meshes, static_cast<size_t>(std::floor(budget)), out.entries, boxes);
  }
  out.top = build_bvh(device, boxes, bvh_top_build(params.width));  // its references: entry indices
  return out;
}

}  // namespace sdfbench
