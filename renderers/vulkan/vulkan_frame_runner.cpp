#include "renderers/vulkan/vulkan_frame_runner.h"

#include <algorithm>
#include <chrono>

#include "renderers/frame_params.h"
#include "renderers/vulkan/loop_cap_probe.h"
#include "renderers/vulkan/vk_error.h"
#include "util/error.h"

namespace sdfbench {
namespace {

constexpr uint32_t kLoopProbeTrips = 2;  // the trip count of render_main.glsl's loop_limit_hit (push constant w)

}  // namespace

VulkanFrameRunner::VulkanFrameRunner(VulkanContext& context, TileKernelFactory kernels, uint32_t counter_kinds,
                                     std::optional<bool> whitted_passes)
    : context_(context),
      kernels_(std::move(kernels)),
      counter_kinds_(counter_kinds),
      whitted_passes_(whitted_passes ? *whitted_passes : has_loop_cap(context)) {
  VkDevice device = context.device();
  VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  alloc.commandPool = context.command_pool();
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  vk_check(vkAllocateCommandBuffers(device, &alloc, &cmd_), "vkAllocateCommandBuffers");
  VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  vk_check(vkCreateFence(device, &fence_info, nullptr, &fence_), "vkCreateFence");
  if (context.has_timestamps()) {
    VkQueryPoolCreateInfo query_info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    query_info.queryType = VK_QUERY_TYPE_TIMESTAMP;
    query_info.queryCount = 2;
    vk_check(vkCreateQueryPool(device, &query_info, nullptr, &queries_), "vkCreateQueryPool");
  }
  frame_ = GpuBuffer(context, sizeof(shading::FrameParams), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, GpuBuffer::Use::Upload,
                     "frame parameters");
}

VulkanFrameRunner::~VulkanFrameRunner() {
  VkDevice device = context_.device();
  vkDeviceWaitIdle(device);
  kernel_.reset();
  if (queries_) vkDestroyQueryPool(device, queries_, nullptr);
  if (fence_) vkDestroyFence(device, fence_, nullptr);
  if (cmd_) vkFreeCommandBuffers(device, context_.command_pool(), 1, &cmd_);
}

void VulkanFrameRunner::set_scene(const Scene& scene, std::vector<KernelBinding> scene_bindings) {
  scene_ = &scene;
  scene_bindings_ = std::move(scene_bindings);
  const ShadingInputs inputs = make_shading_inputs(scene, FrameRequest{1, 1});
  const size_t material_bytes = inputs.materials.size() * sizeof(shading::GpuMaterial);
  const size_t light_bytes = inputs.lights.size() * sizeof(shading::GpuLight);
  materials_ = GpuBuffer(context_, material_bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, GpuBuffer::Use::Upload, "material table");
  materials_.write(inputs.materials.data(), material_bytes);
  lights_ = GpuBuffer(context_, light_bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, GpuBuffer::Use::Upload, "light table");
  lights_.write(inputs.lights.data(), light_bytes);
  // Image textures (binding 5); one dummy texel when there are none, as buffers cannot be empty.
  const glm::vec4 dummy(0.0f);
  const size_t texel_bytes = std::max<size_t>(scene.texels.size(), 1) * sizeof(glm::vec4);
  texels_ = GpuBuffer(context_, texel_bytes, VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT, GpuBuffer::Use::Upload,
                      "image texture texels");
  texels_.write(scene.texels.empty() ? &dummy : scene.texels.data(), texel_bytes);
  texels_.texel_view(VK_FORMAT_R32G32B32A32_SFLOAT, sizeof(glm::vec4));
  // Implicit objects (bindings 30-31); a buffer is never empty (GpuBuffer pads), the count is in the frame.
  const size_t object_bytes = inputs.implicit_objects.size() * sizeof(shading::GpuImplicitObject);
  const size_t node_bytes = inputs.implicit_nodes.size() * sizeof(shading::GpuImplicitNode);
  implicit_objects_ = GpuBuffer(context_, object_bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, GpuBuffer::Use::Upload,
                                "implicit objects");
  if (object_bytes) implicit_objects_.write(inputs.implicit_objects.data(), object_bytes);
  implicit_nodes_ = GpuBuffer(context_, node_bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, GpuBuffer::Use::Upload,
                              "implicit nodes");
  if (node_bytes) implicit_nodes_.write(inputs.implicit_nodes.data(), node_bytes);
  kernel_.reset();
  width_ = height_ = 0;
}

void VulkanFrameRunner::prepare_outputs(uint32_t width, uint32_t height, RenderMode mode, bool counters) {
  if (kernel_ && width == width_ && height == height_ && mode == mode_ && counters == counting_) return;
  kernel_.reset();
  // whitted in passes: a ray stack and a state per invocation of a tile (nothing else uses them).
  const bool passes = mode == RenderMode::Whitted && whitted_passes_;
  const VkDeviceSize slots =
      passes ? VkDeviceSize{(std::min(width, kTileSize) + 7) / 8 * 8} * std::min(height, kTileSize) : 1;
  const VkDeviceSize pixels = static_cast<VkDeviceSize>(width) * height;
  color_ = GpuBuffer(context_, pixels * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, GpuBuffer::Use::Readback,
                     "output image");
  aov_ = GpuBuffer(context_, pixels * sizeof(shading::GpuAov), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                   GpuBuffer::Use::Readback, "output AOVs");
  stacks_ = GpuBuffer(context_, slots * STACK_SIZE * sizeof(shading::PathEntry), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                      GpuBuffer::Use::Upload, "whitted ray stacks");
  // StateBlock: the pending flag (padded to the struct alignment), then a state per slot.
  states_ = GpuBuffer(context_, sizeof(glm::uvec4) + slots * sizeof(shading::PixelState),
                      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, GpuBuffer::Use::Readback, "whitted pixel states");
  // Only instrumented kernels use it; the others get a placeholder (a binding needs a buffer).
  counters_ = GpuBuffer(context_, (counters ? pixels : 1) * COUNTER_KINDS * sizeof(uint32_t),
                        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, GpuBuffer::Use::Readback, "work counters");
  std::vector<KernelBinding> bindings = {
      {0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, &frame_},  {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &materials_},
      {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &lights_}, {3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &color_},
      {4, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &aov_},    {5, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, &texels_},
      {6, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &stacks_}, {7, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &states_},
      {30, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &implicit_objects_},
      {31, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &implicit_nodes_},
      {COUNTERS_BINDING, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &counters_}};
  bindings.insert(bindings.end(), scene_bindings_.begin(), scene_bindings_.end());
  // One kernel per mode (and textures or not, implicit objects or not, counters or not), so that
  // the compiler drops the code a frame cannot use: on lavapipe, branching on them at run time
  // cost ~80 ms per 720p frame.
  kernel_ = kernels_("#define SHADING_MODE " + std::to_string(static_cast<int>(mode)) + "u\n#define SHADING_TEXTURES " +
                         (scene_->texels.empty() ? "false" : "true") + "\n#define SHADING_IMPLICITS " +
                         (scene_->implicits.empty() ? "false" : "true") + "\n#define COUNTERS " + (counters ? "1" : "0") +
                         "\n#define WHITTED_PASSES " + (whitted_passes_ ? "1" : "0") + "\n",
                     bindings);
  width_ = width;
  height_ = height;
  mode_ = mode;
  counting_ = counters;
}

void VulkanFrameRunner::submit(const std::vector<glm::uvec4>& launches, FrameResult& result) {
  VkDevice device = context_.device();
  vk_check(vkResetCommandBuffer(cmd_, 0), "vkResetCommandBuffer");
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  vk_check(vkBeginCommandBuffer(cmd_, &begin), "vkBeginCommandBuffer");
  // The previous pass's shader writes (whitted pixel states) before this pass reads them.
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
  const VkPipelineStageFlags stage = kernel_->stage();
  vkCmdPipelineBarrier(cmd_, stage, stage, 0, 1, &barrier, 0, nullptr, 0, nullptr);
  if (queries_) {
    vkCmdResetQueryPool(cmd_, queries_, 0, 2);
    vkCmdWriteTimestamp(cmd_, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, queries_, 0);
  }
  kernel_->bind(cmd_);
  for (const glm::uvec4& tile : launches)
    kernel_->launch(cmd_, tile, std::min(kTileSize, width_ - tile.x), std::min(kTileSize, height_ - tile.y));
  if (queries_) vkCmdWriteTimestamp(cmd_, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queries_, 1);
  // Make the shader writes visible to the host reads that follow the fence.
  barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(cmd_, stage, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &barrier, 0, nullptr, 0, nullptr);
  vk_check(vkEndCommandBuffer(cmd_), "vkEndCommandBuffer");

  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd_;
  const auto start = std::chrono::steady_clock::now();
  vk_check(vkQueueSubmit(context_.queue(), 1, &submit, fence_), "vkQueueSubmit");
  vk_check(vkWaitForFences(device, 1, &fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  const auto end = std::chrono::steady_clock::now();
  vk_check(vkResetFences(device, 1, &fence_), "vkResetFences");

  result.wall_ms += std::chrono::duration<double, std::milli>(end - start).count();
  if (queries_) {
    uint64_t stamps[2] = {0, 0};
    vk_check(vkGetQueryPoolResults(device, queries_, 0, 2, sizeof(stamps), stamps, sizeof(uint64_t),
                                   VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
             "vkGetQueryPoolResults");
    result.device_ms = std::max(result.device_ms, 0.0) +
                       static_cast<double>(timestamp_ticks(stamps[0], stamps[1], context_.timestamp_valid_bits())) *
                       context_.properties().limits.timestampPeriod * 1e-6;
  }
}

FrameResult VulkanFrameRunner::run(const FrameRequest& request) {
  if (!scene_) throw InternalError("render before prepare");
  const bool passes = request.mode == RenderMode::Whitted && whitted_passes_;
  prepare_outputs(request.width, request.height, request.mode, request.counters);
  const ShadingInputs inputs = make_shading_inputs(*scene_, request);
  frame_.write(&inputs.frame, sizeof(inputs.frame));

  // Tiles keep each launch within maxComputeWorkGroupCount and bound its duration. whitted in
  // passes runs each tile pass after pass, one ray per pixel per pass, until no pixel has rays left.
  FrameResult result;
  std::vector<glm::uvec4> tiles;
  for (uint32_t y = 0; y < request.height; y += kTileSize)
    for (uint32_t x = 0; x < request.width; x += kTileSize) tiles.emplace_back(x, y, 0u, kLoopProbeTrips);
  if (!passes) submit(tiles, result);
  // A pass traces one ray of each pixel's tree, which holds at most 2^(depth + 1) - 1 rays.
  const uint32_t max_passes = (2u << std::min(request.max_depth.value_or(scene_->render.max_depth), MAX_DEPTH_LIMIT)) - 1u;
  for (size_t i = 0; passes && i < tiles.size(); ++i) {
    uint32_t pending = 1;
    for (uint32_t pass = 0; pending != 0 && pass < max_passes; ++pass) {
      pending = 0;
      states_.write(&pending, sizeof(pending));
      submit({glm::uvec4(tiles[i].x, tiles[i].y, pass, kLoopProbeTrips)}, result);
      states_.read(&pending, sizeof(pending));
    }
    if (pending != 0) throw InternalError("whitted passes did not finish within " + std::to_string(max_passes));
  }

  const size_t pixels = static_cast<size_t>(request.width) * request.height;
  std::vector<shading::GpuAov> aov(pixels);
  aov_.read(aov.data(), pixels * sizeof(shading::GpuAov));
  for (const shading::GpuAov& a : aov) {
    result.rays += a.ids.z;
    result.truncated_pixels += a.ids.w != 0u;
    result.bound_pixels += (a.ids.w & shading::CUT_TRAVERSAL_BOUND_BIT) != 0u;
  }
  std::vector<uint32_t> counts;
  if (request.counters) {
    counts.resize(pixels * COUNTER_KINDS);
    counters_.read(counts.data(), counts.size() * sizeof(uint32_t));
    result.counters = sum_counters(counts, counter_kinds_);
  }
  if (request.readback) {
    FrameImages& img = result.images;
    img.width = request.width;
    img.height = request.height;
    img.color.resize(pixels);
    color_.read(img.color.data(), pixels * sizeof(glm::vec4));
    img.depth.resize(pixels);
    img.instance_id.resize(pixels);
    img.primitive_id.resize(pixels);
    img.normal.resize(pixels);
    for (size_t i = 0; i < pixels; ++i) {
      img.depth[i] = aov[i].normal_depth.w;
      img.normal[i] = glm::vec3(aov[i].normal_depth);
      img.instance_id[i] = aov[i].ids.x;
      img.primitive_id[i] = aov[i].ids.y;
    }
    img.steps = pixel_steps(counts, counter_kinds_);
  }
  return result;
}

}  // namespace sdfbench
