// The loop-cap guard (docs/limits.md "The loop limit"), tested on a real capped driver: Debian 12's own
// lavapipe (Mesa 22.3), unpacked by harness/scripts/fetch_old_lavapipe.sh and selected through
// VK_DRIVER_FILES for the test's process (and the sdfbench it starts) only. The default driver
// (Mesa 25) has no cap: the same scenes render in full there.
#include <cstdlib>
#include <filesystem>

#include <gtest/gtest.h>

#include "harness/benchmark_runner.h"
#include "harness/image_agreement.h"
#include "renderers/backend_registry.h"
#include "renderers/renderer.h"
#include "renderers/vulkan/loop_cap_probe.h"
#include "scenes/thesis_layout.h"
#include "tests/test_support.h"
#include "util/error.h"

namespace sdfbench {
namespace {

constexpr const char* kOldLavapipeIcd = SDFBENCH_OLD_LAVAPIPE_ICD;

class OldLavapipe : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(std::filesystem::is_regular_file(kOldLavapipeIcd))
        << kOldLavapipeIcd << " is missing: run harness/scripts/fetch_old_lavapipe.sh (install_deps.sh does)";
    ::setenv("VK_DRIVER_FILES", kOldLavapipeIcd, 1);
  }
};

FrameImages embree_images(const Scene& scene, const FrameRequest& request) {
  auto embree = create_renderer("embree", BackendOptions{});
  embree->prepare(scene);
  return embree->render(request).images;
}

// tri-aabb on thesis:bunny:1000 at 24x14, primary, with Embree's instance ids of the same frame.
struct ThousandBunnies {
  FrameResult frame;
  std::vector<uint32_t> embree_ids;
};
ThousandBunnies render_thousand_bunnies() {
  const Scene scene = make_thesis_scene({"bunny", 1000, 1});
  auto renderer = create_renderer("tri-aabb", BackendOptions{});
  renderer->prepare(scene);
  const FrameRequest request{24, 14, RenderMode::Primary, true};
  return {renderer->render(request), embree_images(scene, request).instance_id};
}

TEST_F(OldLavapipe, ProbeFindsTheCapAndInfoSaysSo) {
  const VulkanContext context(VulkanContext::Options{});
  EXPECT_NE(context.info().driver_info.find("Mesa 22.3"), std::string::npos) << context.info().driver_info;
  EXPECT_TRUE(has_loop_cap(context));
  const test::CommandResult r = test::run_sdfbench("info");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("loop cap: yes"), std::string::npos) << r.output;
}

// Mesa 22.3's lavapipe has no ray tracing: a real device without the extension.
TEST_F(OldLavapipe, VkRtSaysTheDeviceLacksRayTracing) {
  try {
    create_renderer("vk-rt", BackendOptions{});
    FAIL() << "vk-rt was created on Mesa 22.3's lavapipe";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("vk-rt: device 'llvmpipe"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("' lacks VK_KHR_ray_tracing_pipeline"), std::string::npos) << e.what();
  }
  const test::CommandResult r = test::run_sdfbench("info");
  EXPECT_NE(r.output.find("vk-rt:    no: lacks VK_KHR_ray_tracing_pipeline"), std::string::npos) << r.output;
}

TEST(LoopCap, DefaultLavapipeHasNone) {
  const VulkanContext context(VulkanContext::Options{});
  EXPECT_FALSE(has_loop_cap(context)) << context.info().driver_info;
  const test::CommandResult r = test::run_sdfbench("info");
  EXPECT_NE(r.output.find("loop cap: none"), std::string::npos) << r.output;
}

// tri-aabb loops over 1000 instances x 4968 triangles wherever a ray crosses many boxes: far past
// 65535 iterations, so the capped driver ends its loops early and pixels come out wrong.
TEST_F(OldLavapipe, FlagsTriAabbOnAThousandBunnies) {
  const auto [frame, expected] = render_thousand_bunnies();
  EXPECT_GT(frame.truncated_pixels, 0u);
  EXPECT_NE(truncation_error("tri-aabb", frame).find("cut " + std::to_string(frame.truncated_pixels) + " pixels short"),
            std::string::npos);
  // Every pixel that differs from Embree was cut short, so flagged pixels cover them.
  size_t wrong = 0;
  for (size_t i = 0; i < expected.size(); ++i) wrong += frame.images.instance_id[i] != expected[i];
  EXPECT_GE(frame.truncated_pixels, wrong);
}

// The same frame on the default driver runs in full and matches Embree pixel for pixel.
TEST(LoopCap, TriAabbOnAThousandBunniesRunsInFullByDefault) {
  const auto [frame, expected] = render_thousand_bunnies();
  EXPECT_EQ(frame.truncated_pixels, 0u);
  EXPECT_EQ(frame.images.instance_id, expected);
}

// Negative control: small scenes stay below the cap in every mode (whitted in passes there).
TEST_F(OldLavapipe, SmallScenesAreNotFlagged) {
  const Scene scene = make_thesis_scene({"bunny", 10, 1});
  for (const char* backend : {"tri-aabb", "sdf-octree"}) {
    auto renderer = create_renderer(backend, BackendOptions{});
    renderer->prepare(scene);
    for (RenderMode mode : {RenderMode::Primary, RenderMode::Shadow, RenderMode::Whitted})
      EXPECT_EQ(renderer->render(FrameRequest{48, 27, mode, false}).truncated_pixels, 0u) << backend << " " << to_string(mode);
  }
}

TEST_F(OldLavapipe, RenderAndCompareFailAndTableRowsAreMarked) {
  const std::string scene = " --scene thesis:bunny:1000 --size 24x14";
  for (const std::string& command : {"render --backend tri-aabb --frames 1 --warmup 0" + scene,
                                     "compare --backends tri-aabb" + scene}) {
    const test::CommandResult r = test::run_sdfbench(command);
    EXPECT_EQ(r.exit_code, 1) << command << "\n" << r.output;
    EXPECT_NE(r.output.find("lavapipe's loop limit (65535 iterations per invocation) cut"), std::string::npos)
        << command << "\n" << r.output;
    EXPECT_NE(r.output.find("the image and timing are invalid"), std::string::npos) << r.output;
  }

  BenchSettings settings;
  settings.warmup = 0;
  settings.frames = 1;
  settings.check_size = {24, 14};
  BenchmarkRunner runner(settings);
  BenchConfig config;
  config.scene = "thesis:bunny:1000";
  config.backend = "tri-aabb";
  config.size = {24, 14};
  EXPECT_EQ(runner.run(config, 0).agreement.rfind("TRUNCATED: ", 0), 0u);
  config.scene = "thesis:bunny:10";
  const Measurement ok = runner.run(config, 1);
  EXPECT_EQ(ok.agreement, "ok");
  EXPECT_EQ(ok.per_ray[COUNTER_AABB_TESTS], 10.0);  // and the counters' columns filled (primary: every box once per ray)
  EXPECT_GT(ok.per_ray[COUNTER_TRIANGLE_TESTS].value_or(0.0), 0.0);
  EXPECT_FALSE(ok.per_ray[COUNTER_STEPS]);
}

}  // namespace
}  // namespace sdfbench
