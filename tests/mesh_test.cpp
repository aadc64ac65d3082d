#include <algorithm>

#include <gtest/gtest.h>

#include "scenes/mesh.h"
#include "tests/test_support.h"
#include "util/error.h"

namespace sdfbench {
namespace {

TEST(ThesisMeshes, HaveTheThesisTriangleCounts) {
  // Thesis figures 6.3-6.4: bunny 4968, teapot 4032, monkey 968, sphere 768.
  const std::pair<const char*, size_t> expected[] = {{"bunny", 4968}, {"teapot", 4032}, {"monkey", 968}, {"sphere", 768}};
  for (const auto& [name, count] : expected) {
    const Mesh mesh = load_obj(builtin_mesh_path(name), name);
    EXPECT_EQ(mesh.triangle_count(), count) << name;
    EXPECT_EQ(mesh.normals.size(), mesh.positions.size()) << name;
    // Normalised by the generator: largest extent 2, centred.
    EXPECT_NEAR(std::max({mesh.bounds.extent().x, mesh.bounds.extent().y, mesh.bounds.extent().z}), 2.0f, 1e-4f) << name;
  }
}

TEST(ObjLoader, RejectsOutOfRangeAndNegativeIndices) {
  test::TempDir dir;
  const auto too_big = dir.write("big.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
  const auto too_small = dir.write("small.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -9\n");
  EXPECT_THROW(load_obj(too_big, "big"), Error);
  EXPECT_THROW(load_obj(too_small, "small"), Error);
}

TEST(ObjLoader, RejectsEmptyAndNonFiniteMeshes) {
  test::TempDir dir;
  EXPECT_THROW(load_obj(dir.write("empty.obj", "# nothing\n"), "empty"), Error);
  EXPECT_THROW(load_obj(dir.write("nan.obj", "v 0 0 1e999\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), "nan"), Error);
  EXPECT_THROW(load_obj(dir.path() / "missing.obj", "missing"), Error);
}

TEST(ObjLoader, TriangulatesPolygonsAndComputesNormals) {
  test::TempDir dir;
  const Mesh quad = load_obj(dir.write("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"), "quad");
  ASSERT_EQ(quad.triangle_count(), 2u);
  for (const glm::vec3& n : quad.normals) EXPECT_NEAR(n.z, 1.0f, 1e-6f);
}

TEST(ObjLoader, SphereNormalsPointOutwards) {
  const Mesh sphere = load_obj(builtin_mesh_path("sphere"), "sphere");
  for (size_t i = 0; i < sphere.positions.size(); ++i)
    EXPECT_GT(glm::dot(sphere.normals[i], glm::normalize(sphere.positions[i] - sphere.bounds.center())), 0.95f) << i;
}

}  // namespace
}  // namespace sdfbench
