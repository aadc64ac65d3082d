#pragma once
// A compiled render kernel (render_main.glsl) that VulkanFrameRunner launches tile by tile: a
// compute pipeline (tri-aabb, the SDF backends) or a ray-tracing pipeline (vk-rt). The runner
// owns the frame's buffers, tiles, barriers, timestamps and read-back; the kernel only records
// its launch.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

#include "renderers/vulkan/compute_kernel.h"
#include "renderers/vulkan/descriptor_set.h"

namespace sdfbench {

class TileKernel {
 public:
  virtual ~TileKernel() = default;
  virtual void bind(VkCommandBuffer cmd) const = 0;
  // One invocation per pixel of a width x height tile; `tile` is render_main.glsl's push constant.
  virtual void launch(VkCommandBuffer cmd, const glm::uvec4& tile, uint32_t width, uint32_t height) const = 0;
  // The pipeline stage its shaders run in (for the runner's barriers).
  virtual VkPipelineStageFlags stage() const = 0;
};

// Builds a kernel for one frame configuration: `defines` are the #defines render_main.glsl is
// compiled with (mode, textures, implicit objects, counters, whitted passes).
using TileKernelFactory =
    std::function<std::unique_ptr<TileKernel>(const std::string& defines, const std::vector<KernelBinding>& bindings)>;

// The compute kernel of an embedded .comp shader (8 x 8 invocations per work group), its SPIR-V
// compiled once per set of defines; `extra_defines` go before every frame configuration's.
TileKernelFactory compute_tile_kernels(const VulkanContext& context, const std::string& shader_name,
                                       const std::string& extra_defines = "");

}  // namespace sdfbench
