#pragma once
#include <optional>
#include <string>

#include "renderers/renderer.h"
#include "renderers/sdf_global/global_field.h"
#include "renderers/sdf/sphere_tracer.h"
#include "renderers/sdf_bricks/brick_field_tables.h"
#include "renderers/sdf_vk/sdf_gpu_tables.h"
#include "renderers/vulkan/vulkan_frame_runner.h"
#include "renderers/vulkan/vulkan_renderer.h"

namespace sdfbench {

// sdf-global (issue 29): one sampled field over the whole scene (renderers/sdf_global/global_field.h),
// sphere-traced in sdf_global.comp with one field sample per step whatever the number of
// instances; near a surface the instances its brick lists are intersected exactly (the mesh
// grids' triangle lists), or --hit field takes the field's own crossing. Its parameters
// (backend_params.h): --global-voxel, --sdf-format, --brick-band, --brick-fetch.
class SdfGlobalRenderer : public VulkanRenderer {
 public:
  explicit SdfGlobalRenderer(const BackendOptions& options);
  std::string name() const override { return "sdf-global"; }
  void prepare(const Scene& scene) override;
  FrameResult render(const FrameRequest& request) override { return runner_.run(request); }
  std::optional<StructureStats> structure_stats() const override { return stats_; }

 private:
  BackendOptions options_;
  sdf::GlobalFieldParams field_params_;
  sdf::SphereTraceParams tracing_;
  std::optional<StructureStats> stats_;  // mesh grids + the global field and its lists
  bool sampler_ = false;  // --brick-fetch, resolved
  SdfGpuTables tables_;
  BrickFieldTables field_tables_;
  GpuBuffer brick_lists_;
  GpuBuffer ref_cells_, ref_sets_;  // --exact-lists triangles
  VulkanFrameRunner runner_;  // declared last: destroyed first, before the buffers it binds
};

// The global field parameters of `params` (--global-voxel, --sdf-format, --brick-band), their
// typed values as resolve_params checked them against their declarations.
sdf::GlobalFieldParams global_field_params(const BackendParams& params, uint64_t max_bytes);


}  // namespace sdfbench
