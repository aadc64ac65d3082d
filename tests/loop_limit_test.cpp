// lavapipe's loop limit (README "The loop limit"): the kernels' probe flags the pixels it cut
// short, and render, compare and benchmark rows refuse to report them.
#include <gtest/gtest.h>

#include "harness/benchmark_runner.h"
#include "harness/image_agreement.h"
#include "renderers/renderer.h"
#include "scenes/thesis_layout.h"
#include "tests/test_support.h"

namespace sdfbench {
namespace {

// tri-aabb loops over 1000 instances x 4968 triangles wherever a ray crosses many boxes: far past
// 65535 iterations, so the limiter ends its loops early and pixels come out wrong.
TEST(LoopLimit, FlagsTriAabbOnAThousandBunnies) {
  const Scene scene = make_thesis_scene({"bunny", 1000, 1});
  auto renderer = create_renderer("tri-aabb", BackendOptions{});
  renderer->prepare(scene);
  const FrameResult frame = renderer->render(FrameRequest{24, 14, RenderMode::Primary, true});
  EXPECT_GT(frame.truncated_pixels, 0u);
  EXPECT_NE(truncation_error("tri-aabb", frame).find("cut " + std::to_string(frame.truncated_pixels) + " pixels short"),
            std::string::npos);
  // Every pixel that differs from Embree was cut short, so flagged pixels cover them.
  auto embree = create_renderer("embree", BackendOptions{});
  embree->prepare(scene);
  const FrameImages expected = embree->render(FrameRequest{24, 14, RenderMode::Primary, true}).images;
  size_t wrong = 0;
  for (size_t i = 0; i < expected.instance_id.size(); ++i) wrong += frame.images.instance_id[i] != expected.instance_id[i];
  EXPECT_GE(frame.truncated_pixels, wrong);
}

// Negative control: a small scene stays far below the limit in every mode, with the same probe.
TEST(LoopLimit, SmallScenesAreNotFlagged) {
  const Scene scene = make_thesis_scene({"bunny", 10, 1});
  for (const char* backend : {"tri-aabb", "sdf-octree"}) {
    auto renderer = create_renderer(backend, BackendOptions{});
    renderer->prepare(scene);
    for (RenderMode mode : {RenderMode::Primary, RenderMode::Shadow, RenderMode::Whitted})
      EXPECT_EQ(renderer->render(FrameRequest{48, 27, mode, false}).truncated_pixels, 0u) << backend << " " << to_string(mode);
  }
}

TEST(LoopLimit, RenderAndCompareFailAndTableRowsAreMarked) {
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
  EXPECT_EQ(ok.aabb_tests_per_ray, 10.0);  // and the counters' columns filled (primary: every box once per ray)
  EXPECT_GT(ok.triangle_tests_per_ray.value_or(0.0), 0.0);
  EXPECT_FALSE(ok.steps_per_ray);
}

}  // namespace
}  // namespace sdfbench
