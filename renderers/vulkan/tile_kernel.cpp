#include "renderers/vulkan/tile_kernel.h"

#include <map>

#include "renderers/vulkan/shader_compiler.h"

namespace sdfbench {
namespace {

constexpr uint32_t kGroupSize = 8;  // render_main.glsl's local_size_x and local_size_y

class ComputeTileKernel : public TileKernel {
 public:
  ComputeTileKernel(const VulkanContext& context, const std::vector<uint32_t>& spirv,
                    const std::vector<KernelBinding>& bindings)
      : kernel_(context, spirv, bindings, static_cast<uint32_t>(sizeof(glm::uvec4))) {}

  void bind(VkCommandBuffer cmd) const override { kernel_.bind(cmd); }
  void launch(VkCommandBuffer cmd, const glm::uvec4& tile, uint32_t width, uint32_t height) const override {
    kernel_.push(cmd, &tile, sizeof(tile));
    vkCmdDispatch(cmd, (width + kGroupSize - 1) / kGroupSize, (height + kGroupSize - 1) / kGroupSize, 1);
  }
  VkPipelineStageFlags stage() const override { return VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT; }

 private:
  ComputeKernel kernel_;
};

}  // namespace

TileKernelFactory compute_tile_kernels(const VulkanContext& context, const std::string& shader_name,
                                       const std::string& extra_defines) {
  auto compiled = std::make_shared<std::map<std::string, std::vector<uint32_t>>>();
  return [&context, shader_name, extra_defines, compiled](const std::string& defines,
                                                          const std::vector<KernelBinding>& bindings) {
    std::vector<uint32_t>& spirv = (*compiled)[defines];
    if (spirv.empty()) spirv = compile_shader(shader_name, extra_defines + defines);
    return std::make_unique<ComputeTileKernel>(context, spirv, bindings);
  };
}

}  // namespace sdfbench
