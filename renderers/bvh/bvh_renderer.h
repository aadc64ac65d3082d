#pragma once
#include <memory>

#include "renderers/bvh/bvh_layouts.h"
#include "renderers/bvh/bvh_scene.h"
#include "renderers/embree/embree_api.h"
#include "renderers/renderer.h"
#include "renderers/vulkan/gpu_buffer.h"
#include "renderers/vulkan/triangle_buffers.h"
#include "renderers/vulkan/vulkan_frame_runner.h"
#include "renderers/vulkan/vulkan_renderer.h"

namespace sdfbench {

// A BVH traced in a Vulkan compute kernel (bvh.comp): the fair triangle baseline for the SDF
// structures, run the way they are run, on the same device. Built on the CPU by Embree's BVH
// builder (bvh_builder.h) at --bvh-width children a node, laid out as --bvh-nodes says
// (bvh_layouts.h), with the top level --bvh-top makes (bvh_scene.h).
class BvhRenderer : public VulkanRenderer {
 public:
  explicit BvhRenderer(const BackendOptions& options);
  ~BvhRenderer() override;
  std::string name() const override { return "bvh"; }
  void prepare(const Scene& scene) override;
  FrameResult render(const FrameRequest& request) override { return runner_.run(request); }
  std::optional<StructureStats> structure_stats() const override { return stats_; }
  // Inner-node depths of the prepared scene's BVHs: the top level's (flat: the one tree's) and the
  // deepest mesh's. The traversal stack holds width - 1 items per level of both.
  struct Depths {
    uint32_t top = 0, meshes = 0;
  };
  Depths depths() const { return depths_; }
  // For tests: a stack of `entries` (fewer than the BVH needs) from the next prepare on, to show
  // that an overflow is reported (as cut pixels), never a silent miss. 0: as deep as the BVH.
  void limit_stack_for_testing(uint32_t entries) { stack_limit_ = entries; }
  // For tests: at most `visits` node visits per ray (fewer than its nodes), to show that reaching
  // the iteration bound is reported as cut pixels. 0: the bound the tables give.
  void limit_visits_for_testing(uint32_t visits) { visit_limit_ = visits; }

 private:
  RTCDevice embree_ = nullptr;  // for its BVH builder only
  BvhSceneParams params_;
  BvhNodes nodes_ = BvhNodes::Float;
  std::unique_ptr<TriangleBuffers> tables_;
  GpuBuffer node_table_, entry_table_, flat_ids_;
  std::optional<StructureStats> stats_;
  Depths depths_;
  uint32_t stack_size_ = 1;
  uint32_t stack_limit_ = 0;
  uint32_t visit_limit_ = 0;
  TileKernelFactory kernels_;  // bvh.comp; the runner's factory adds the layout's and the scene's #defines
  VulkanFrameRunner runner_;  // declared last: destroyed first, before the buffers it binds
};

}  // namespace sdfbench
