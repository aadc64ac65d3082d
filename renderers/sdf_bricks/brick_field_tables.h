#pragma once
// Sampled brick fields (BrickGpuArrays) uploaded for a kernel, bound at 18-21 as
// brick_field_bindings.glsl declares them: shared by sdf-bricks (a field per mesh) and sdf-global
// (the scene's one field). With --brick-fetch sampler the atlas is a filtered 3D image.
#include <string>
#include <vector>

#include "renderers/renderer.h"
#include "renderers/sdf_bricks/brick_gpu_arrays.h"
#include "renderers/sdf_vk/sdf_gpu_arrays.h"
#include "renderers/vulkan/descriptor_set.h"
#include "renderers/vulkan/gpu_buffer.h"
#include "renderers/vulkan/gpu_image.h"
#include "renderers/vulkan/vulkan_context.h"

namespace sdfbench {

// --brick-fetch as used on `device`: "auto" is the sampler on a GPU (hardware filtering) and, on
// a CPU device (lavapipe), what measured faster there (docs/backends.md, "sdf-bricks").
bool use_sampler(const std::string& brick_fetch, const VulkanDeviceInfo& device);

// --hit field: rays leave a field hit from this many of the scene's largest voxels off it (the
// hit lies within a fraction of a voxel, on either side).
inline constexpr float kFieldHitOffsetVoxels = 2.0f;

// --sdf-format, --brick-band and --brick-fetch: the parameters both sampled fields own (their
// declarations; renderers/backend_params.h).
std::vector<ParamSpec> brick_field_param_specs();
sdf::SdfFormat sdf_format_param(const BackendParams& params);

// The defines both sampled-field kernels take: the fetch path, --hit field, u8 values, storage tables.
std::string brick_kernel_defines(const BackendOptions& options, bool sampler);

class BrickFieldTables {
 public:
  BrickFieldTables() = default;
  // Puts the atlas image's layout and the sampler's filter slack into `params` (sampler only).
  // `hint` says what makes the tables smaller.
  BrickFieldTables(const VulkanContext& context, const BrickGpuArrays& arrays, bool sampler, shading::SdfParams& params,
                   const char* hint);
  void add_bindings(std::vector<KernelBinding>& bindings) const;

 private:
  bool sampler_ = false;
  GpuBuffer records_, slots_, atlas_, coarse_;
  GpuImage3D image_;
};

}  // namespace sdfbench
