#include "renderers/tri_aabb/tri_aabb_renderer.h"

#include "renderers/shading/gpu_types.h"

namespace sdfbench {
namespace shading {
#include "tri_aabb_types.glsl"
}

TriAabbRenderer::TriAabbRenderer(const BackendOptions& options)
    : context_(VulkanContext::Options{options.device, options.validation}), runner_(context_, "tri_aabb.comp", kTriAabbCounters, options.whitted_passes) {}

void TriAabbRenderer::prepare(const Scene& scene) {
  // Triangles of every mesh, concatenated; 3 texels per triangle.
  std::vector<glm::vec4> vertices, normals;
  std::vector<uint32_t> first_triangle;
  for (const Mesh& mesh : scene.meshes) {
    first_triangle.push_back(static_cast<uint32_t>(vertices.size() / 3));
    for (const glm::uvec3& t : mesh.triangles) {
      for (int k = 0; k < 3; ++k) {
        vertices.emplace_back(mesh.positions[t[k]], 1.0f);
        normals.emplace_back(mesh.normals[t[k]], 0.0f);
      }
    }
  }
  std::vector<shading::TriInstance> instances;
  for (const Instance& instance : scene.instances) {
    const Aabb bounds = scene.world_bounds(instance);
    shading::TriInstance g{};
    g.bounds_min = glm::vec4(bounds.min, 0.0f);
    g.bounds_max = glm::vec4(bounds.max, 0.0f);
    g.world_to_object = instance.transform.world_to_object();
    g.object_to_world = instance.transform.object_to_world();
    g.info = glm::uvec4(first_triangle[instance.mesh], scene.meshes[instance.mesh].triangle_count(), instance.material, 0u);
    instances.push_back(g);
  }
  const VkBufferUsageFlags texel = VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT;
  instances_ = GpuBuffer(context_, instances.size() * sizeof(shading::TriInstance), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                         GpuBuffer::Use::Upload, "instance table");
  instances_.write(instances.data(), instances.size() * sizeof(shading::TriInstance));
  vertices_ = GpuBuffer(context_, vertices.size() * sizeof(glm::vec4), texel, GpuBuffer::Use::Upload, "triangle vertices");
  vertices_.write(vertices.data(), vertices.size() * sizeof(glm::vec4));
  vertices_.texel_view(VK_FORMAT_R32G32B32A32_SFLOAT, sizeof(glm::vec4));
  normals_ = GpuBuffer(context_, normals.size() * sizeof(glm::vec4), texel, GpuBuffer::Use::Upload, "triangle normals");
  normals_.write(normals.data(), normals.size() * sizeof(glm::vec4));
  normals_.texel_view(VK_FORMAT_R32G32B32A32_SFLOAT, sizeof(glm::vec4));
  runner_.set_scene(scene, {{8, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &instances_},
                            {9, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, &vertices_},
                            {10, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, &normals_}});
}

}  // namespace sdfbench
