#pragma once
#include <string>
#include <vector>

#include "renderers/renderer.h"
#include "renderers/sdf_bricks/brick_field.h"
#include "renderers/sdf/scene_hash.h"
#include "renderers/sdf/sphere_tracer.h"
#include "renderers/sdf_bricks/brick_field_tables.h"
#include "renderers/sdf_vk/sdf_gpu_tables.h"
#include "renderers/vulkan/vulkan_frame_runner.h"
#include "renderers/vulkan/vulkan_renderer.h"

namespace sdfbench {

// sdf-bricks (issue 28): the thesis' scene hash and octree lists (as sdf-octree) over per-mesh
// sampled brick fields (renderers/sdf_bricks/brick_field.h), sphere-traced in sdf_bricks.comp. Its
// parameters are its own (backend_params.h): --voxels, --sdf-format, --brick-band, --brick-trace.
class SdfBricksRenderer : public VulkanRenderer {
 public:
  explicit SdfBricksRenderer(const BackendOptions& options);
  std::string name() const override { return "sdf-bricks"; }
  void prepare(const Scene& scene) override;
  FrameResult render(const FrameRequest& request) override { return runner_.run(request); }
  std::optional<StructureStats> structure_stats() const override { return stats_; }

 private:
  BackendOptions options_;
  sdf::BrickFieldParams field_params_;
  sdf::SceneHashParams hash_params_;
  sdf::SphereTraceParams tracing_;
  std::optional<StructureStats> stats_;  // mesh grids + scene hash + brick fields
  SdfGpuTables tables_;
  bool sampler_ = false;  // --brick-fetch, resolved: the atlas as a filtered 3D image
  BrickFieldTables brick_tables_;
  VulkanFrameRunner runner_;  // declared last: destroyed first, before the buffers it binds
};

// The brick field parameters of `params` (--voxels, --sdf-format, --brick-band), their typed
// values as resolve_params checked them against their declarations.
sdf::BrickFieldParams brick_field_params(const BackendParams& params, uint64_t max_bytes);


}  // namespace sdfbench
