// bvh, the BVH in a compute kernel: images agree with Embree on every thesis mesh in every mode,
// and a scene built to make its BVH deep traces with no stack overflow and no miss (the trees'
// invariants and quality figures: bvh_tree_test.cpp; every layout and top level: bvh_layouts_test.cpp).
#include <algorithm>
#include <limits>
#include <memory>
#include <utility>
#include <set>

#include <vector>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "harness/image_agreement.h"
#include "renderers/backend_registry.h"
#include "renderers/bvh/bvh_renderer.h"
#include "renderers/embree/embree_api.h"
#include "renderers/shading/gpu_types.h"
#include "scenes/mesh.h"
#include "scenes/thesis_layout.h"
#include "tests/test_support.h"

namespace sdfbench {
namespace {

using test::render_frame;

void expect_agrees_with_embree(const Scene& scene, RenderMode mode, uint32_t w, uint32_t h) {
  test::expect_agrees_with_embree("bvh", scene, mode, w, h);
}

class BvhVsEmbree : public testing::TestWithParam<test::MeshMode> {};

TEST_P(BvhVsEmbree, ImagesAgree) {
  expect_agrees_with_embree(make_thesis_scene({GetParam().mesh, 30, 1}), GetParam().mode, 96, 54);
}

INSTANTIATE_TEST_SUITE_P(ThesisMeshes, BvhVsEmbree, testing::ValuesIn(test::thesis_meshes_in_every_mode()),
                         [](const auto& info) { return test::mesh_mode_name(info.param); });

TEST(Bvh, RotatedScaledInstancesAgreeWithEmbree) {
  Scene scene = make_thesis_scene({"bunny", 6, 3});
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    Transform& t = scene.instances[i].transform;
    t.rotation = glm::angleAxis(0.5f + 1.1f * static_cast<float>(i), glm::normalize(glm::vec3(-1.0f, 2.0f, 0.5f + i)));
    t.scale *= 0.5f + 0.35f * static_cast<float>(i % 3);
  }
  for (RenderMode mode : {RenderMode::Primary, RenderMode::Shadow, RenderMode::Whitted})
    expect_agrees_with_embree(scene, mode, 128, 72);
}

// 40 spheres growing by half from one corner, each box holding all the smaller ones: the surface
// area heuristic peels big ones off first, so the instance BVH is deeper (13 levels) than a
// balanced tree of 40 leaves (6). Every ray still finds its hit.
TEST(Bvh, DeepInstanceTreeTracesWithoutOverflow) {
  Scene scene = make_thesis_scene({"sphere", 1, 1});
  const Instance ball = scene.instances[0];
  const glm::vec3 centre = scene.meshes[0].bounds.center();
  const float radius = 0.5f * scene.meshes[0].bounds.extent().x;
  scene.instances.clear();
  const int count = 40;
  for (int i = 0; i < count; ++i) {
    Instance s = ball;
    s.transform.rotation = glm::quat(1, 0, 0, 0);
    s.transform.scale = 0.02f * std::pow(1.5f, static_cast<float>(i));
    // The sphere's box touches the corner (0, 0, 0) from above.
    s.transform.translation = glm::vec3(s.transform.scale * radius) - s.transform.scale * centre;
    scene.instances.push_back(s);
  }
  scene.camera = {.position = {-1.0f, 0.6f, -1.0f}, .look_at = {0.05f, 0.02f, 0.05f}, .up = {0, 1, 0}, .fov_y_degrees = 40};
  BackendOptions options;
  options.params.set("bvh_width", "2");
  const std::unique_ptr<Renderer> created = create_renderer("bvh", options);
  auto& renderer = dynamic_cast<BvhRenderer&>(*created);
  renderer.prepare(scene);
  EXPECT_GT(renderer.depths().top, 10u) << "the scene was meant to make a deep instance BVH";
  for (RenderMode mode : {RenderMode::Primary, RenderMode::Shadow}) {
    const FrameResult frame = renderer.render(FrameRequest{64, 36, mode, true});
    EXPECT_EQ(frame.truncated_pixels, 0u);
    const FrameImages reference = render_frame("embree", scene, mode, 64, 36);
    size_t hits = 0;
    for (uint32_t id : reference.instance_id) hits += id < shading::FLOOR_INSTANCE_VALUE;
    EXPECT_GT(hits, 64u * 36u / 10) << "the spheres should fill part of the frame";
    const Agreement g = compare_frames(frame.images, reference);
    EXPECT_GE(g.hit_percent, 99.9);
    EXPECT_GE(g.id_percent, 99.9);
  }
  // The negative control: a stack too small for that BVH is reported (cut pixels, the CLI's
  // TRUNCATED row), not a silent miss.
  renderer.limit_stack_for_testing(3);
  renderer.prepare(scene);
  EXPECT_GT(renderer.render(FrameRequest{64, 36, RenderMode::Primary, true}).truncated_pixels, 0u);
}

// Every layout and top level (a covering array: each pair of width, nodes and top appears), and
// Embree's packets and flat scene, agree with the reference (single rays over instances) on
// rotated, scaled and overlapping instances in every mode.
struct Variant {
  const char* backend;
  std::vector<std::pair<const char*, const char*>> params;
};
class LayoutsVsEmbree : public testing::TestWithParam<Variant> {};

TEST_P(LayoutsVsEmbree, ImagesAgree) {
  // Twelve bunnies in a cluster in front of the camera (3 x 4, neighbours overlapping), rotated and scaled.
  Scene scene = make_thesis_scene({"bunny", 12, 5});
  const Aabb mesh = scene.meshes[0].bounds;
  const float size = glm::length(mesh.extent());
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    Transform& t = scene.instances[i].transform;
    t.rotation = glm::angleAxis(0.3f + 0.9f * static_cast<float>(i), glm::normalize(glm::vec3(1.0f, 0.5f + i, -0.5f)));
    t.scale = 0.6f + 0.3f * static_cast<float>(i % 4);
    t.translation = glm::vec3(0.45f * size * static_cast<float>(i % 4), 0.4f * size * static_cast<float>(i / 4), 0.0f) -
                    t.scale * (t.rotation * mesh.center());
  }
  const Aabb cluster = scene.instance_bounds();
  scene.camera = {.position = cluster.center() + glm::vec3(0.2f, 0.3f, -1.6f) * glm::length(cluster.extent()),
                  .look_at = cluster.center(), .up = {0, 1, 0}, .fov_y_degrees = 40};
  BackendOptions options;
  for (const auto& [name, value] : GetParam().params) options.params.set(name, value);
  auto renderer = create_renderer(GetParam().backend, options);
  renderer->prepare(scene);
  auto embree = create_renderer("embree", BackendOptions{});
  embree->prepare(scene);
  for (RenderMode mode : {RenderMode::Primary, RenderMode::Shadow, RenderMode::Whitted}) {
    const FrameRequest request{96, 54, mode, true};
    const FrameResult frame = renderer->render(request);
    EXPECT_EQ(frame.truncated_pixels, 0u);
    const FrameImages reference = embree->render(request).images;
    size_t instance_pixels = 0;  // agreement on floor and sky alone would prove nothing
    for (uint32_t id : reference.instance_id) instance_pixels += id < shading::FLOOR_INSTANCE_VALUE;
    EXPECT_GE(instance_pixels, reference.instance_id.size() / 50) << to_string(mode);
    const Agreement g = compare_frames(frame.images, reference);
    EXPECT_GE(g.hit_percent, 99.9) << to_string(mode);
    EXPECT_GE(g.id_percent, 99.9) << to_string(mode);
    EXPECT_LE(g.depth_p99, 1e-4) << to_string(mode);
    EXPECT_GE(g.psnr, 45.0) << to_string(mode);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Bvh, LayoutsVsEmbree,
    testing::Values(Variant{"bvh", {{"bvh_width", "2"}, {"bvh_nodes", "float"}, {"bvh_top", "instanced"}}},
                    Variant{"bvh", {{"bvh_width", "2"}, {"bvh_nodes", "quantised"}, {"bvh_top", "rebraided"}}},
                    Variant{"bvh", {{"bvh_width", "2"}, {"bvh_nodes", "float"}, {"bvh_top", "flat"}}},
                    Variant{"bvh", {{"bvh_width", "4"}, {"bvh_nodes", "quantised"}, {"bvh_top", "instanced"}}},
                    Variant{"bvh", {{"bvh_width", "4"}, {"bvh_nodes", "float"}, {"bvh_top", "rebraided"}}},
                    Variant{"bvh", {{"bvh_width", "4"}, {"bvh_nodes", "quantised"}, {"bvh_top", "flat"}}},
                    Variant{"bvh", {{"bvh_width", "8"}, {"bvh_nodes", "float"}, {"bvh_top", "instanced"}}},
                    Variant{"bvh", {{"bvh_width", "8"}, {"bvh_nodes", "quantised"}, {"bvh_top", "rebraided"}}},
                    Variant{"bvh", {{"bvh_width", "8"}, {"bvh_nodes", "float"}, {"bvh_top", "flat"}}},
                    Variant{"embree", {{"embree_rays", "packets"}, {"embree_scene", "instanced"}}},
                    Variant{"embree", {{"embree_rays", "single"}, {"embree_scene", "flat"}}},
                    Variant{"embree", {{"embree_rays", "packets"}, {"embree_scene", "flat"}}}),
    [](const auto& info) {
      std::string name = info.param.backend;
      for (const auto& [key, value] : info.param.params) name += std::string("_") + value;
      return name;
    });

TEST(Bvh, SceneWithoutInstancesDrawsTheFloor) {
  Scene scene = make_thesis_scene({"sphere", 1, 1});
  scene.instances.clear();
  const FrameImages reference = render_frame("embree", scene, RenderMode::Shadow, 48, 27);
  const FrameImages images = render_frame("bvh", scene, RenderMode::Shadow, 48, 27);
  EXPECT_EQ(images.instance_id, reference.instance_id);
}

}  // namespace
}  // namespace sdfbench
