#pragma once
// The GPU tables of the triangle backends (triangle_tables.glsl, bindings 8-10): every mesh's
// triangles concatenated (3 texels of positions and of vertex normals per triangle) and the
// instance table. tri-aabb intersects them itself; vk-rt builds its acceleration structures from
// the same vertex buffer and shades from the same normals.
#include <vector>

#include "renderers/vulkan/descriptor_set.h"
#include "renderers/vulkan/gpu_buffer.h"
#include "scenes/scene.h"

namespace sdfbench {

// How a backend wants the tables laid out (bvh: in its leaves' order).
struct TriangleLayout {
  std::vector<std::vector<uint32_t>> triangles;  // per mesh: its triangles in table order (repeats allowed)
  std::vector<uint32_t> roots;                   // per mesh: a value for its instances' info.w (bvh: the BVH root)
};

struct TriangleBuffers {
  // extra_vertex_usage: usage flags the vertex buffer needs beyond a texel buffer (vk-rt:
  // acceleration-structure build input, device address). Without a layout: every mesh's
  // triangles once, in Morton order, info.w 0.
  TriangleBuffers(const VulkanContext& context, const Scene& scene, VkBufferUsageFlags extra_vertex_usage = 0,
                  const TriangleLayout* layout = nullptr);

  std::vector<KernelBinding> bindings() const;

  GpuBuffer instances, vertices, normals;
  std::vector<uint32_t> first_triangle;  // per mesh, into vertices / 3
  std::vector<uint32_t> triangle_count;  // per mesh: its entries in the tables
};

}  // namespace sdfbench
