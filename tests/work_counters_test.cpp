// Work counters of instrumented frames (docs/commands.md "Counters"): sdf-cpu and the Vulkan kernel count
// the same work, the counts are plausible, timed frames count nothing, and the docs list the counters.
#include <filesystem>
#include <fstream>
#include <numeric>
#include <random>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "harness/measurement.h"
#include "renderers/backend_registry.h"
#include "renderers/renderer.h"
#include "renderers/sdf/traced_distance.h"
#include "scenes/thesis_layout.h"
#include "tests/test_support.h"

namespace sdfbench {
namespace {

constexpr uint32_t kWidth = 64, kHeight = 36;

FrameResult instrumented_frame(Renderer& renderer, RenderMode mode) {
  FrameRequest request{kWidth, kHeight, mode, true};
  request.counters = true;
  return renderer.render(request);
}

double per_ray(const FrameResult& frame, uint32_t kind) {
  return static_cast<double>(frame.counters[kind].value()) / static_cast<double>(frame.rays);
}

// The same structures (cell 10, octree depth 4), the same algorithm and shortcuts: the same work,
// up to a float contraction that makes a ray take a step more or less here and there.
TEST(WorkCounters, SdfCpuAndSdfOctreeCountTheSameWork) {
  const Scene scene = make_thesis_scene({"bunny", 100, 3});
  auto cpu = create_renderer("sdf-cpu", BackendOptions{});
  cpu->prepare(scene);
  BackendOptions options;
  options.validation = true;  // the instrumented kernel and its counter buffer run clean too
  auto gpu = create_renderer("sdf-octree", options);
  gpu->prepare(scene);
  for (RenderMode mode : {RenderMode::Primary, RenderMode::Shadow, RenderMode::Whitted}) {
    SCOPED_TRACE(to_string(mode));
    const FrameResult expected = instrumented_frame(*cpu, mode);
    const FrameResult frame = instrumented_frame(*gpu, mode);
    EXPECT_NEAR(static_cast<double>(frame.rays), static_cast<double>(expected.rays), 0.001 * expected.rays);
    for (uint32_t k = 0; k < COUNTER_KINDS; ++k) {
      SCOPED_TRACE(counter_names()[k]);
      if (!(kSdfCounters & counter_bit(k))) {  // field_samples: sdf-bricks' only
        EXPECT_FALSE(frame.counters[k].has_value());
        EXPECT_FALSE(expected.counters[k].has_value());
        continue;
      }
      ASSERT_TRUE(frame.counters[k].has_value());  // triangle_tests: the exact hit's ray-triangle tests
      if (!frame.counters[k]) continue;
      ASSERT_TRUE(expected.counters[k]);
      if (k != COUNTER_OUT_OF_STEPS) {  // a clean scene's rays may run out of none
        EXPECT_GT(*frame.counters[k], 0u);
      }
      EXPECT_NEAR(per_ray(frame, k), per_ray(expected, k), 0.01 * per_ray(expected, k));
    }
    // Plausible: every instance evaluation follows a box test, and a step evaluates at most the
    // leaf's instances; hits need steps; the heat map sums to the total.
    EXPECT_GE(*frame.counters[COUNTER_AABB_TESTS], *frame.counters[COUNTER_INSTANCE_EVALS]);
    EXPECT_LT(per_ray(frame, COUNTER_STEPS), 100.0);
    ASSERT_EQ(frame.images.steps.size(), size_t{kWidth} * kHeight);
    EXPECT_EQ(std::accumulate(frame.images.steps.begin(), frame.images.steps.end(), uint64_t{0}),
              *frame.counters[COUNTER_STEPS]);
    size_t hits = 0, same_steps = 0;
    for (size_t i = 0; i < frame.images.steps.size(); ++i) {
      if (frame.images.instance_id[i] < shading::FLOOR_INSTANCE_VALUE) {
        ++hits;
        EXPECT_GE(frame.images.steps[i], 1u);
      }
      same_steps += frame.images.steps[i] == expected.images.steps[i];
    }
    EXPECT_GT(hits, 100u);
    EXPECT_GE(same_steps, frame.images.steps.size() * 99 / 100);
    EXPECT_EQ(frame.truncated_pixels, 0u);
  }
  EXPECT_EQ(gpu->validation_messages(), 0u);
}

// tri-aabb tests every instance's box once per primary ray, and triangles only inside hit boxes.
TEST(WorkCounters, TriAabbTestsEveryBoxOncePerPrimaryRay) {
  const Scene scene = make_thesis_scene({"sphere", 10, 1});
  auto renderer = create_renderer("tri-aabb", BackendOptions{});
  renderer->prepare(scene);
  const FrameResult frame = instrumented_frame(*renderer, RenderMode::Primary);
  EXPECT_EQ(frame.counters[COUNTER_AABB_TESTS], uint64_t{10} * kWidth * kHeight);
  ASSERT_TRUE(frame.counters[COUNTER_TRIANGLE_TESTS]);
  EXPECT_GT(*frame.counters[COUNTER_TRIANGLE_TESTS], 0u);
  EXPECT_LT(*frame.counters[COUNTER_TRIANGLE_TESTS], uint64_t{10} * 768 * kWidth * kHeight);
  EXPECT_FALSE(frame.counters[COUNTER_STEPS]);
  EXPECT_TRUE(frame.images.steps.empty());
}

TEST(WorkCounters, EmbreeAndTimedFramesReportNone) {
  const Scene scene = make_thesis_scene({"sphere", 10, 1});
  auto embree = create_renderer("embree", BackendOptions{});
  embree->prepare(scene);
  for (const std::optional<uint64_t>& c : instrumented_frame(*embree, RenderMode::Primary).counters) EXPECT_FALSE(c);
  auto sdf = create_renderer("sdf-cpu", BackendOptions{});
  sdf->prepare(scene);
  const FrameResult timed = sdf->render(FrameRequest{kWidth, kHeight, RenderMode::Primary, true});
  for (const std::optional<uint64_t>& c : timed.counters) EXPECT_FALSE(c);
  EXPECT_TRUE(timed.images.steps.empty());
}

// docs/commands.md documents the counter table as it is: its "Counters" table is the one
// counters_markdown() generates from renderers/work_counter_list.h, and its CSV columns list the
// counters' columns in the CSV's order; harness/scripts/update_docs.sh writes both.
TEST(WorkCounters, DocsListEveryCounterAsTheTableHasIt) {
  const std::filesystem::path doc = std::filesystem::path(SDFBENCH_DATA_DIR).parent_path() / "docs" / "commands.md";
  const char* regenerate = ": stale; run harness/scripts/update_docs.sh (it writes `sdfbench backends --counters-markdown "
                           "table|csv-columns` there)";
  std::ifstream in(doc);
  ASSERT_TRUE(in) << doc;
  std::string per_ray_cell;  // the CSV columns' row of the counters: "| steps_per_ray, ..., cell_sets_per_ray |"
  for (const std::string& column : counter_columns()) per_ray_cell += (per_ray_cell.empty() ? "| " : ", ") + column;
  per_ray_cell += " | ";
  std::string block;  // between the markers, as update_docs.sh writes it: a blank line either side of the table
  int starts = 0, ends = 0;
  bool in_block = false, has_per_ray_row = false;
  for (std::string line; std::getline(in, line);) {
    has_per_ray_row |= line.rfind(per_ray_cell, 0) == 0;
    if (line.rfind("<!-- counters: ", 0) == 0) {
      ++starts;
      in_block = true;
    } else if (line == "<!-- end counters -->") {
      ++ends;
      in_block = false;
    } else if (in_block) {
      block += line + "\n";
    }
  }
  ASSERT_EQ(starts, 1) << doc << ": one \"<!-- counters: ...\" line before the Counters table";
  ASSERT_EQ(ends, 1) << doc << ": one \"<!-- end counters -->\" line after it";
  const std::string table = std::string("\n").append(counters_markdown()).append("\n");
  EXPECT_EQ(block, table) << doc << ": the \"Counters\" table" << regenerate;
  EXPECT_TRUE(has_per_ray_row) << doc << ": no CSV column row starting " << per_ray_cell << regenerate;
}

// The shortcuts change the work, never the distance, instance or triangle.
TEST(TracedDistance, SameAnswerAsSceneDistanceWithLessWork) {
  const Scene scene = make_thesis_scene({"bunny", 30, 2});
  const sdf::SceneSdf sdf = sdf::build_scene_sdf(scene, {}, {});
  const sdf::TraceCulling culling = sdf::make_trace_culling(scene, sdf);
  const Aabb box = scene.instance_bounds();
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  uint64_t full = 0, traced = 0;
  for (int i = 0; i < 2000; ++i) {
    const glm::vec3 p = box.min + glm::vec3(u(rng), u(rng), u(rng)) * box.extent();
    const sdf::SceneDistance a = sdf::scene_distance(sdf, scene, p);
    const sdf::SceneDistance b = sdf::traced_scene_distance(sdf, scene, culling, p);
    ASSERT_EQ(b.distance, a.distance) << i;
    ASSERT_EQ(b.instance, a.instance) << i;
    ASSERT_EQ(b.triangle, a.triangle) << i;
    ASSERT_LE(b.evaluations, a.evaluations);
    full += a.evaluations;
    traced += b.evaluations;
  }
  EXPECT_LT(traced, full);
}

TEST(Heatmap, RenderWritesStepsPerPixel) {
  test::TempDir dir;
  const auto png = dir.path() / "steps.png";
  const test::CommandResult r = test::run_sdfbench(
      "render --scene thesis:bunny:10 --backend sdf-octree --size 48x27 --frames 1 --warmup 0 --heatmap " + png.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("counters per ray"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("steps per pixel"), std::string::npos) << r.output;
  auto in = OIIO::ImageInput::open(png.string());
  ASSERT_TRUE(in) << OIIO::geterror();
  const OIIO::ImageSpec& spec = in->spec();
  ASSERT_EQ(spec.width, 48);
  ASSERT_EQ(spec.height, 27);
  ASSERT_EQ(spec.nchannels, 3);
  std::vector<unsigned char> pixels(48 * 27 * 3);
  ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, pixels.data()));
  // Not one flat colour: the bunnies' pixels took more steps than the sky's.
  EXPECT_GT(*std::max_element(pixels.begin(), pixels.end()), *std::min_element(pixels.begin(), pixels.end()) + 100);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), {}), 1);  // no temporary file left

  const test::CommandResult tri = test::run_sdfbench(
      "render --scene thesis:sphere:5 --backend tri-aabb --size 32x18 --frames 1 --heatmap " + png.string());
  EXPECT_EQ(tri.exit_code, 1) << tri.output;
  EXPECT_NE(tri.output.find("--heatmap maps sphere-tracing steps"), std::string::npos) << tri.output;
}

}  // namespace
}  // namespace sdfbench
