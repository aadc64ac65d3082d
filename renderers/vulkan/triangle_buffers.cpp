#include "renderers/vulkan/triangle_buffers.h"

#include <algorithm>
#include <limits>

#include "renderers/shading/gpu_types.h"
#include "util/morton.h"

namespace sdfbench {
namespace shading {
#include "triangle_instance.glsl"
}

namespace {

// The mesh's triangles in Morton order of their centroids. A BVH builder that splits primitives in
// the order given (lavapipe's, Mesa 25.0) gets spatially coherent halves; the triangle tests of
// tri-aabb are the same in any order.
std::vector<uint32_t> spatial_order(const Mesh& mesh) {
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const glm::vec3& p : mesh.positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  std::vector<std::pair<uint32_t, uint32_t>> keyed;
  keyed.reserve(mesh.triangles.size());
  for (uint32_t i = 0; i < mesh.triangles.size(); ++i) {
    const glm::uvec3& t = mesh.triangles[i];
    const glm::vec3 centroid = (mesh.positions[t.x] + mesh.positions[t.y] + mesh.positions[t.z]) / 3.0f;
    keyed.emplace_back(morton_code(centroid, lo, hi), i);
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<uint32_t> order;
  order.reserve(keyed.size());
  for (const auto& [code, i] : keyed) order.push_back(i);
  return order;
}

}  // namespace

TriangleBuffers::TriangleBuffers(const VulkanContext& context, const Scene& scene, VkBufferUsageFlags extra_vertex_usage,
                                 const TriangleLayout* layout) {
  std::vector<glm::vec4> vertex_data, normal_data;
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    first_triangle.push_back(static_cast<uint32_t>(vertex_data.size() / 3));
    const std::vector<uint32_t> order = layout ? layout->triangles.at(m) : spatial_order(mesh);
    triangle_count.push_back(static_cast<uint32_t>(order.size()));
    for (uint32_t triangle : order) {
      const glm::uvec3& t = mesh.triangles[triangle];
      for (int k = 0; k < 3; ++k) {
        vertex_data.emplace_back(mesh.positions[t[k]], 1.0f);
        // w of the first normal: the triangle's index in the mesh, for the primitive-id AOV.
        normal_data.emplace_back(mesh.normals[t[k]], k == 0 ? glm::uintBitsToFloat(triangle) : 0.0f);
      }
    }
  }
  std::vector<shading::TriInstance> instance_data;
  for (const Instance& instance : scene.instances) {
    const Aabb bounds = scene.world_bounds(instance);
    shading::TriInstance g{};
    g.bounds_min = glm::vec4(bounds.min, 0.0f);
    g.bounds_max = glm::vec4(bounds.max, 0.0f);
    g.world_to_object = instance.transform.world_to_object();
    g.object_to_world = instance.transform.object_to_world();
    g.info = glm::uvec4(first_triangle[instance.mesh], triangle_count[instance.mesh], instance.material,
                        layout ? layout->roots.at(instance.mesh) : 0u);
    instance_data.push_back(g);
  }
  const VkBufferUsageFlags texel = VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT;
  instances = GpuBuffer(context, instance_data.size() * sizeof(shading::TriInstance), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                        GpuBuffer::Use::Upload, "instance table");
  instances.write(instance_data.data(), instance_data.size() * sizeof(shading::TriInstance));
  vertices = GpuBuffer(context, vertex_data.size() * sizeof(glm::vec4), texel | extra_vertex_usage, GpuBuffer::Use::Upload,
                       "triangle vertices");
  vertices.write(vertex_data.data(), vertex_data.size() * sizeof(glm::vec4));
  vertices.texel_view(VK_FORMAT_R32G32B32A32_SFLOAT, sizeof(glm::vec4));
  normals = GpuBuffer(context, normal_data.size() * sizeof(glm::vec4), texel, GpuBuffer::Use::Upload, "triangle normals");
  normals.write(normal_data.data(), normal_data.size() * sizeof(glm::vec4));
  normals.texel_view(VK_FORMAT_R32G32B32A32_SFLOAT, sizeof(glm::vec4));
}

std::vector<KernelBinding> TriangleBuffers::bindings() const {
  return {{8, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &instances},
          {9, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, &vertices},
          {10, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, &normals}};
}

}  // namespace sdfbench
