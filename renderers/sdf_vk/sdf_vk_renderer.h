#pragma once
#include <string>

#include "renderers/renderer.h"
#include "renderers/sdf/scene_hash.h"
#include "renderers/sdf/sphere_tracer.h"
#include "renderers/sdf_vk/sdf_gpu_tables.h"
#include "renderers/vulkan/vulkan_context.h"
#include "renderers/vulkan/vulkan_frame_runner.h"

namespace sdfbench {

// The thesis' renderer, Vulkan compute: sphere tracing through the scene hash (+ octrees) and
// the per-mesh distance grids. One class, one kernel (sdf_trace.comp) for both backends:
// "sdf-hash" builds with octree depth 0 and hash cell 1 (thesis table 6.2), "sdf-octree" with
// the given octree parameters (table 6.1); each declares the parameters it owns.
struct BackendInfo;
BackendInfo sdf_hash_backend();    // their entries in renderers/backend_registry.h
BackendInfo sdf_octree_backend();

class SdfVkRenderer : public Renderer {
 public:
  SdfVkRenderer(std::string name, const BackendOptions& options);
  std::string name() const override { return name_; }
  std::string device_name() const override { return context_.info().name; }
  std::string driver_name() const override { return context_.info().driver + " " + context_.info().driver_info; }
  void prepare(const Scene& scene) override;
  FrameResult render(const FrameRequest& request) override { return runner_.run(request); }
  uint32_t validation_messages() const override { return context_.validation_messages(); }
  std::optional<StructureStats> structure_stats() const override { return stats_; }

 private:
  std::string name_;
  BackendOptions options_;
  std::optional<StructureStats> stats_;  // of the CPU structures the GPU tables were flattened from
  VulkanContext context_;
  sdf::SphereTraceParams tracing_;
  sdf::SceneHashParams hash_params_;  // sdf-hash: octree depth 0 (it owns no octree parameters)
  SdfGpuTables tables_;
  VulkanFrameRunner runner_;  // declared last: destroyed first, before the buffers it binds
};

}  // namespace sdfbench
