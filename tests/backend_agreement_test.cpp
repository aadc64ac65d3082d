// Every backend must draw what Embree draws (the independent reference), per thesis mesh.
#include <gtest/gtest.h>

#include "harness/image_agreement.h"
#include "renderers/renderer.h"
#include "renderers/shading/gpu_types.h"
#include "scenes/thesis_layout.h"
#include "tests/test_support.h"

namespace sdfbench {
namespace {

using test::render_frame;

struct AgreementCase {
  const char* mesh;
  uint32_t count;
  RenderMode mode;
};

class TriAabbVsEmbree : public testing::TestWithParam<AgreementCase> {};

TEST_P(TriAabbVsEmbree, ImagesAgree) {
  const AgreementCase& c = GetParam();
  const Scene scene = make_thesis_scene({c.mesh, c.count, 1});
  const FrameImages reference = render_frame("embree", scene, c.mode, 96, 54);
  const FrameImages images = render_frame("tri-aabb", scene, c.mode, 96, 54);
  // Not a black or empty picture: some pixels hit instances, some the floor, some the sky.
  size_t instance = 0, floor = 0, sky = 0;
  for (uint32_t id : reference.instance_id) {
    instance += id < shading::FLOOR_INSTANCE_VALUE;
    floor += id == shading::FLOOR_INSTANCE_VALUE;
    sky += id == shading::NO_INSTANCE_VALUE;
  }
  EXPECT_GT(instance, 0u);
  EXPECT_GT(floor, 0u);
  EXPECT_GT(sky, 0u);
  const Agreement g = compare_frames(images, reference);
  EXPECT_GE(g.hit_percent, 99.5);
  EXPECT_GE(g.id_percent, 99.0);
  EXPECT_LE(g.depth_p99, 1e-3);
  EXPECT_GE(g.psnr, 35.0);
}

INSTANTIATE_TEST_SUITE_P(ThesisMeshes, TriAabbVsEmbree,
                         testing::Values(AgreementCase{"bunny", 30, RenderMode::Primary},
                                         AgreementCase{"teapot", 30, RenderMode::Primary},
                                         AgreementCase{"monkey", 30, RenderMode::Primary},
                                         AgreementCase{"sphere", 30, RenderMode::Primary},
                                         AgreementCase{"bunny", 30, RenderMode::Shadow},
                                         AgreementCase{"sphere", 100, RenderMode::Shadow}),
                         [](const auto& info) {
                           return std::string(info.param.mesh) + "_" + std::to_string(info.param.count) + "_" +
                                  to_string(info.param.mode);
                         });

// Known answer: one sphere mesh (radius 1 after normalisation) at a known distance in front
// of the camera; the centre pixel's depth is the distance to the tessellated surface.
TEST(KnownAnswer, SphereDepthAtImageCentre) {
  Scene scene = make_thesis_scene({"sphere", 1, 1});
  scene.floor.enabled = false;
  Instance& ball = scene.instances[0];
  ball.transform = Transform{};
  ball.transform.translation = -scene.meshes[0].bounds.center();
  scene.camera = {.position = {0, 0, 10}, .look_at = {0, 0, 0}, .up = {0, 1, 0}, .fov_y_degrees = 30};
  for (const char* backend : {"embree", "tri-aabb"}) {
    const FrameImages f = render_frame(backend, scene, RenderMode::Primary, 33, 33);
    const size_t centre = 16 * 33 + 16;
    EXPECT_LT(f.instance_id[centre], shading::FLOOR_INSTANCE_VALUE) << backend;
    // The UV sphere's faces lie inside the unit sphere by at most 1 - cos(pi / 12) (13 rings).
    EXPECT_NEAR(f.depth[centre], 9.0f, 0.035f) << backend;
    EXPECT_GT(f.normal[centre].z, 0.98f) << backend;
    EXPECT_EQ(f.instance_id[0], shading::NO_INSTANCE_VALUE) << backend;  // corner sees the sky
  }
}

}  // namespace
}  // namespace sdfbench
