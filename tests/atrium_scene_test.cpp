// The generated interior (issue 38, part 3): its spec and errors, determinism, its size and
// materials, and every backend drawing it as Embree does from an aisle (mirrors and glass in
// view of the whitted check in compare's own tests; here primary and shadow rays, the strict gate).
#include <string>

#include <gtest/gtest.h>

#include "scenes/atrium_scene.h"
#include "scenes/scene_source.h"
#include "tests/test_support.h"
#include "util/error.h"

namespace sdfbench {
namespace {

TEST(Atrium, SpecsAndTheirErrors) {
  EXPECT_EQ(parse_atrium_spec("atrium").detail, 4u);
  EXPECT_EQ(parse_atrium_spec("atrium:2:1").detail, 2u);
  EXPECT_EQ(parse_atrium_spec("atrium:2:1").camera, 1u);
  for (const char* bad : {"atrium:0", "atrium:9", "atrium:4:3", "atrium:x", "atrium:1:2:3", "atrium:", "atriums"}) {
    try {
      load_scene(bad);
      ADD_FAILURE() << bad << " was accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    }
  }
}

TEST(Atrium, IsDeterministicWithSharedMeshesAndItsMaterials) {
  const Scene a = make_atrium_scene({}), b = make_atrium_scene({});
  ASSERT_EQ(a.meshes.size(), b.meshes.size());
  for (size_t m = 0; m < a.meshes.size(); ++m) EXPECT_EQ(a.meshes[m].positions, b.meshes[m].positions) << m;
  EXPECT_GE(a.triangle_count(), 200000u);  // "a few hundred thousand"
  EXPECT_LE(a.triangle_count(), 400000u);
  EXPECT_LT(make_atrium_scene({.detail = 1}).triangle_count(), a.triangle_count() / 10);
  EXPECT_LT(a.meshes.size() * 4, a.instances.size()) << "columns and arches are instances of shared meshes";
  bool mirror = false, glass = false;
  for (const Instance& i : a.instances) {
    mirror = mirror || a.materials[i.material].reflectance >= 0.5f;
    glass = glass || a.materials[i.material].transmission >= 0.5f;
  }
  EXPECT_TRUE(mirror && glass);
  EXPECT_TRUE(a.floor.enabled);
}

class AtriumBackends : public ::testing::TestWithParam<std::string> {};

TEST_P(AtriumBackends, DrawWhatEmbreeDraws) {
  const Scene scene = make_atrium_scene({.detail = 1, .camera = 2});
  for (RenderMode mode : {RenderMode::Primary, RenderMode::Shadow})
    test::expect_agrees_with_embree(GetParam(), scene, mode, 96, 54);
}

INSTANTIATE_TEST_SUITE_P(EveryBackend, AtriumBackends, ::testing::ValuesIn(test::backends_but_the_reference()),
                         [](const auto& info) { return test::backend_test_name(info.param); });

}  // namespace
}  // namespace sdfbench
