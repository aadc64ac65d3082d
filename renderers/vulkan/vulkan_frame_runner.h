#pragma once
// What every Vulkan backend shares: the shading inputs (frame, materials, lights, texels, implicit
// objects), the output image + AOV buffers, tiled launches, timestamps and read-back. A backend
// adds its scene bindings (>= 8) and says how its kernel is built (tile_kernel.h).
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "renderers/renderer.h"
#include "renderers/vulkan/gpu_buffer.h"
#include "renderers/vulkan/tile_kernel.h"
#include "renderers/vulkan/vulkan_context.h"

namespace sdfbench {

class VulkanFrameRunner {
 public:
  static constexpr uint32_t kTileSize = 256;  // pixels per side of one launch

  // counter_kinds: the work counters the kernel counts (bit k for COUNTER kind k).
  // whitted_passes: BackendOptions::whitted_passes (unset: the device's loop cap decides).
  VulkanFrameRunner(VulkanContext& context, TileKernelFactory kernels, uint32_t counter_kinds,
                    std::optional<bool> whitted_passes);
  ~VulkanFrameRunner();
  VulkanFrameRunner(const VulkanFrameRunner&) = delete;
  VulkanFrameRunner& operator=(const VulkanFrameRunner&) = delete;

  // Keeps the scene for the frame parameters and uploads materials, lights, texels and implicit objects.
  void set_scene(const Scene& scene, std::vector<KernelBinding> scene_bindings);
  FrameResult run(const FrameRequest& request);

 private:
  void prepare_outputs(uint32_t width, uint32_t height, RenderMode mode, bool counters);
  // Records `launches` (tile x, y, whitted pass), submits, waits; adds the times to `result`.
  void submit(const std::vector<glm::uvec4>& launches, FrameResult& result);

  VulkanContext& context_;
  TileKernelFactory kernels_;
  uint32_t counter_kinds_;
  const Scene* scene_ = nullptr;
  std::vector<KernelBinding> scene_bindings_;
  GpuBuffer frame_, materials_, lights_, texels_, implicit_objects_, implicit_nodes_, color_, aov_, stacks_, states_,
      counters_;
  uint32_t width_ = 0, height_ = 0;
  RenderMode mode_ = RenderMode::Primary;
  bool counting_ = false;
  bool whitted_passes_;  // one ray per pixel per dispatch (render_main.glsl, WHITTED_PASSES)
  std::unique_ptr<TileKernel> kernel_;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  VkQueryPool queries_ = VK_NULL_HANDLE;
};

}  // namespace sdfbench
