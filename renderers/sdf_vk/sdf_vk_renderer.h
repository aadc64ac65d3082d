#pragma once
#include <string>

#include "renderers/renderer.h"
#include "renderers/sdf/scene_hash.h"
#include "renderers/sdf/sphere_tracer.h"
#include "renderers/sdf_vk/sdf_gpu_tables.h"
#include "renderers/vulkan/vulkan_frame_runner.h"
#include "renderers/vulkan/vulkan_renderer.h"

namespace sdfbench {

// The thesis' renderer, Vulkan compute: sphere tracing through the scene hash (+ octrees) and
// the per-mesh distance grids. One class, one kernel (sdf_trace.comp) for both backends:
// "sdf-hash" builds with octree depth 0 and hash cell 1 (thesis table 6.2), "sdf-octree" with
// the given octree parameters (table 6.1); each declares the parameters it owns.
class SdfVkRenderer : public VulkanRenderer {
 public:
  SdfVkRenderer(std::string name, const BackendOptions& options);
  std::string name() const override { return name_; }
  void prepare(const Scene& scene) override;
  FrameResult render(const FrameRequest& request) override { return runner_.run(request); }
  std::optional<StructureStats> structure_stats() const override { return stats_; }

 private:
  std::string name_;
  BackendOptions options_;
  std::optional<StructureStats> stats_;  // of the CPU structures the GPU tables were flattened from
  sdf::SphereTraceParams tracing_;
  sdf::SceneHashParams hash_params_;  // sdf-hash: octree depth 0 (it owns no octree parameters)
  SdfGpuTables tables_;
  VulkanFrameRunner runner_;  // declared last: destroyed first, before the buffers it binds
};

// Its entry in the backend registry (renderers/backend_registry.h).
struct BackendInfo;
BackendInfo sdf_hash_backend();
BackendInfo sdf_octree_backend();

}  // namespace sdfbench
