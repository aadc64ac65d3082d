// The Vulkan path runs clean under VK_LAYER_KHRONOS_validation; a negative control proves the
// message counter actually sees validation errors.
#include <gtest/gtest.h>

#include "renderers/backend_registry.h"
#include "renderers/renderer.h"
#include "renderers/vulkan/vulkan_context.h"
#include "scenes/thesis_layout.h"

namespace sdfbench {
namespace {

// GPUs with fewer than 64 timestamp bits (issue 17): the elapsed ticks are taken modulo 2^bits,
// so a counter that wrapped between the two stamps still gives the true interval.
TEST(VulkanTimestamps, TicksCountOnlyTheValidBits) {
  EXPECT_EQ(timestamp_ticks(100, 250, 64), 150u);
  EXPECT_EQ(timestamp_ticks(100, 250, 36), 150u);
  EXPECT_EQ(timestamp_ticks((uint64_t(1) << 36) - 10, 5, 36), 15u);                    // wrapped
  EXPECT_EQ(timestamp_ticks(uint64_t(7) << 36 | 100, uint64_t(3) << 36 | 130, 36), 30u);  // junk above the valid bits
  EXPECT_EQ(timestamp_ticks(~uint64_t(0) - 1, 3, 64), 5u);
}

TEST(VulkanValidation, TriAabbRendersWithoutValidationMessages) {
  BackendOptions options;
  options.validation = true;
  auto renderer = create_renderer("tri-aabb", options);
  const Scene scene = make_thesis_scene({"monkey", 10, 1});
  renderer->prepare(scene);
  for (RenderMode mode : {RenderMode::Primary, RenderMode::Shadow}) {
    renderer->render(FrameRequest{64, 36, mode, true});
    renderer->render(FrameRequest{300, 20, mode, false});  // a second size: outputs and kernel rebuilt
  }
  EXPECT_EQ(renderer->validation_messages(), 0u);
}

// vk-rt: acceleration-structure builds and compaction, the ray-tracing pipeline and its shader
// binding table, every mode, an instrumented frame, whitted in one invocation and in passes.
TEST(VulkanValidation, VkRtRendersWithoutValidationMessages) {
  for (bool passes : {false, true}) {
    BackendOptions options;
    options.validation = true;
    options.whitted_passes = passes;
    auto renderer = create_renderer("vk-rt", options);
    const Scene monkeys = make_thesis_scene({"monkey", 10, 1}), bunnies = make_thesis_scene({"bunny", 3, 2});
    renderer->prepare(monkeys);
    for (RenderMode mode : {RenderMode::Primary, RenderMode::Shadow, RenderMode::Whitted}) {
      renderer->render(FrameRequest{64, 36, mode, true});
      renderer->render(FrameRequest{300, 20, mode, false, std::nullopt, true});  // another size, counters
    }
    renderer->prepare(bunnies);  // structures rebuilt for another scene
    renderer->render(FrameRequest{32, 18, RenderMode::Shadow, true});
    EXPECT_EQ(renderer->validation_messages(), 0u) << "whitted passes " << passes;
  }
}

TEST(VulkanValidation, BvhRendersWithoutValidationMessages) {
  BackendOptions options;
  options.validation = true;
  auto renderer = create_renderer("bvh", options);
  const Scene scene = make_thesis_scene({"teapot", 10, 1});
  renderer->prepare(scene);
  for (RenderMode mode : {RenderMode::Primary, RenderMode::Shadow, RenderMode::Whitted}) {
    renderer->render(FrameRequest{64, 36, mode, true});
    renderer->render(FrameRequest{300, 20, mode, false, std::nullopt, true});  // another size, counters
  }
  EXPECT_EQ(renderer->validation_messages(), 0u);
}

TEST(VulkanValidation, NegativeControlInvalidUsageIsCounted) {
  VulkanContext context(VulkanContext::Options{"lavapipe", true});
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = 0;  // invalid: VUID-VkBufferCreateInfo-size-00912
  info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  VkBuffer buffer = VK_NULL_HANDLE;
  if (vkCreateBuffer(context.device(), &info, nullptr, &buffer) == VK_SUCCESS && buffer)
    vkDestroyBuffer(context.device(), buffer, nullptr);
  EXPECT_GT(context.validation_messages(), 0u);
}

}  // namespace
}  // namespace sdfbench
