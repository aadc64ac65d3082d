#include "renderers/bvh/bvh_renderer.h"

#include <algorithm>
#include <chrono>

#include "renderers/backend.h"
#include "renderers/bvh/bvh_builder.h"
#include "util/error.h"

namespace sdfbench {
namespace {

// Measured on lavapipe (thesis:bunny:1000, primary, 640x360): leaves of 1, 2 or 4 triangles
// trace alike (1.80, 1.78, 1.79 Mrays/s), 8 slower (1.68); spatial splits (HIGH) beat binned SAH
// (MEDIUM) by 7 % (1.79 vs 1.67). One instance a top-level leaf.
BvhBuildParams mesh_params() { return BvhBuildParams{RTC_BUILD_QUALITY_HIGH, 4}; }
BvhBuildParams top_params() { return BvhBuildParams{RTC_BUILD_QUALITY_MEDIUM, 1}; }

// Applies `f(child, count)` to both children of every node (the w components of BvhNode).
template <typename F>
void for_each_child(std::vector<BvhNode>& nodes, F f) {
  for (BvhNode& n : nodes) {
    uint32_t left = glm::floatBitsToUint(n.left_min.w), right = glm::floatBitsToUint(n.left_max.w);
    f(left, glm::floatBitsToUint(n.right_min.w));
    f(right, glm::floatBitsToUint(n.right_max.w));
    n.left_min.w = glm::uintBitsToFloat(left);
    n.left_max.w = glm::uintBitsToFloat(right);
  }
}

void check_depth(const FlatBvh& bvh, const BvhBuildParams& params, const std::string& what) {
  if (bvh.depth > params.max_depth)
    throw Error("bvh: the BVH of " + what + " is " + std::to_string(bvh.depth) + " levels deep, more than the " +
                std::to_string(params.max_depth) + " the builder allows");
}

GpuBuffer node_buffer(const VulkanContext& context, const std::vector<BvhNode>& nodes, const char* what) {
  GpuBuffer buffer(context, nodes.size() * sizeof(BvhNode), VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT,
                   GpuBuffer::Use::Upload, what);
  buffer.write(nodes.data(), nodes.size() * sizeof(BvhNode));
  buffer.texel_view(VK_FORMAT_R32G32B32A32_SFLOAT, sizeof(glm::vec4));
  return buffer;
}

}  // namespace

BvhRenderer::BvhRenderer(const BackendOptions& options)
    : VulkanRenderer(options),
      kernels_(compute_tile_kernels(context_, "bvh.comp")),
      runner_(
          context_,
          [this](const std::string& defines, const std::vector<KernelBinding>& bindings) {
            std::string limits = "#define BVH_STACK_SIZE " + std::to_string(stack_size_) + "\n";
            if (visit_limit_ > 0) limits += "#define BVH_VISIT_LIMIT " + std::to_string(visit_limit_) + "u\n";
            return kernels_(defines + limits, bindings);
          },
          kBvhCounters, options.whitted_passes) {
  const std::string config = "threads=" + std::to_string(cpu_thread_count(options));
  embree_ = rtcNewDevice(config.c_str());
  if (!embree_) throw Error("Embree: rtcNewDevice failed (error " + std::to_string(rtcGetDeviceError(nullptr)) + ")");
}

BvhRenderer::~BvhRenderer() { rtcReleaseDevice(embree_); }

void BvhRenderer::prepare(const Scene& scene) {
  const auto start = std::chrono::steady_clock::now();
  // Every mesh's BVH, concatenated; leaves name slots in the mesh's part of the triangle tables.
  TriangleLayout layout;
  std::vector<BvhNode> mesh_nodes;
  Depths depths;
  for (const Mesh& mesh : scene.meshes) {
    FlatBvh bvh = build_mesh_bvh(embree_, mesh, mesh_params());
    check_depth(bvh, mesh_params(), "mesh '" + mesh.name + "'");
    depths.meshes = std::max(depths.meshes, bvh.depth);
    const uint32_t root = static_cast<uint32_t>(mesh_nodes.size());
    for_each_child(bvh.nodes, [root](uint32_t& child, uint32_t count) {
      if (count == 0) child += root;  // inner nodes: into the concatenated array
    });
    mesh_nodes.insert(mesh_nodes.end(), bvh.nodes.begin(), bvh.nodes.end());
    layout.triangles.push_back(std::move(bvh.references));
    layout.roots.push_back(root);
  }
  // The instances' BVH: one instance a leaf, the leaf's child its instance id.
  std::vector<Aabb> boxes;
  for (const Instance& instance : scene.instances) boxes.push_back(scene.world_bounds(instance));
  FlatBvh top = build_bvh(embree_, boxes, top_params());
  check_depth(top, top_params(), "the instances");
  depths.top = top.depth;
  for_each_child(top.nodes, [&top](uint32_t& child, uint32_t count) {
    if (count > 0 && child < top.references.size()) child = top.references[child];
  });

  tables_ = std::make_unique<TriangleBuffers>(context_, scene, 0, &layout);
  mesh_nodes_ = node_buffer(context_, mesh_nodes, "mesh BVH nodes");
  top_nodes_ = node_buffer(context_, top.nodes, "instance BVH nodes");
  StructureStats stats;
  stats.build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  // The nodes and the triangles' vertices in leaf order (what the traversal reads).
  stats.bytes = (mesh_nodes.size() + top.nodes.size()) * sizeof(BvhNode) + tables_->vertices.size();
  stats_ = stats;
  std::vector<KernelBinding> bindings = tables_->bindings();
  bindings.push_back({11, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, &mesh_nodes_});
  bindings.push_back({12, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, &top_nodes_});
  depths_ = depths;
  // Before set_scene: the kernels are built for it. Rounded up to 8, so that most scenes share a
  // kernel (lavapipe compiles each variant anew: the test suite's main cost).
  const uint32_t deepest = std::max({depths.top, depths.meshes, 1u});
  stack_size_ = stack_limit_ > 0 ? std::min(deepest, stack_limit_) : (deepest + 7u) / 8u * 8u;
  runner_.set_scene(scene, bindings);
}

BackendInfo bvh_backend() {
  return {.name = "bvh", .kind = BackendKind::ComputeBvh,
          .summary = "a two-level SAH BVH (Embree's builder) traversed in a Vulkan compute kernel",
          .counters = true, .create = factory<BvhRenderer>()};
}

}  // namespace sdfbench
