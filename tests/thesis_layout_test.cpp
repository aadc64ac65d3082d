#include <gtest/gtest.h>

#include "scenes/thesis_layout.h"
#include "util/error.h"

namespace sdfbench {
namespace {

TEST(ThesisLayout, ParsesSpecs) {
  const ThesisLayoutSpec a = parse_thesis_spec("thesis:bunny:100");
  EXPECT_EQ(a.mesh, "bunny");
  EXPECT_EQ(a.count, 100u);
  EXPECT_EQ(a.seed, 1u);
  EXPECT_EQ(parse_thesis_spec("thesis:sphere:3:42").seed, 42u);
  for (const char* bad : {"thesis:bunny", "thesis:cube:10", "thesis:bunny:0", "thesis:bunny:-3", "thesis:bunny:ten",
                          "thesis:bunny:10:x", "thesis:bunny:10:1:2", "thesis:bunny:1000000"})
    EXPECT_THROW(parse_thesis_spec(bad), Error) << bad;
}

TEST(ThesisLayout, IsDeterministicPerSeedAndDiffersAcrossSeeds) {
  const Scene a = make_thesis_scene({"sphere", 50, 7});
  const Scene b = make_thesis_scene({"sphere", 50, 7});
  const Scene c = make_thesis_scene({"sphere", 50, 8});
  ASSERT_EQ(a.instances.size(), 50u);
  for (size_t i = 0; i < a.instances.size(); ++i) {
    EXPECT_EQ(a.instances[i].transform.translation, b.instances[i].transform.translation);
    EXPECT_EQ(a.instances[i].transform.scale, b.instances[i].transform.scale);
  }
  EXPECT_NE(a.instances[0].transform.translation, c.instances[0].transform.translation);
}

TEST(ThesisLayout, ObjectsStayInTheRegionWithoutOverlap) {
  const Scene scene = make_thesis_scene({"bunny", 1000, 1});
  ASSERT_EQ(scene.instances.size(), 1000u);
  const Aabb bounds = scene.instance_bounds();
  // Bounding boxes of rotated objects stay inside the 140 x 100 x 140 region (floor at y = 0).
  EXPECT_GE(bounds.min.x, -70.0f);
  EXPECT_GE(bounds.min.y, 0.0f);
  EXPECT_LE(bounds.max.x, 70.0f);
  EXPECT_LE(bounds.max.y, 100.0f);
  EXPECT_LE(bounds.max.z, 70.0f);
  // Bounding spheres are disjoint.
  const float mesh_radius = 0.5f * glm::length(scene.meshes[0].bounds.extent());
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    const Aabb bi = scene.world_bounds(scene.instances[i]);
    for (size_t j = i + 1; j < scene.instances.size(); ++j) {
      const Aabb bj = scene.world_bounds(scene.instances[j]);
      const float ri = mesh_radius * scene.instances[i].transform.scale;
      const float rj = mesh_radius * scene.instances[j].transform.scale;
      ASSERT_GE(glm::length(bi.center() - bj.center()) + 1e-3f, ri + rj) << i << " " << j;
    }
  }
}

}  // namespace
}  // namespace sdfbench
