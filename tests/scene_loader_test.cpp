// The descriptor loader rejects bad input with a message naming the file, the field and the problem.
#include <gtest/gtest.h>

#include "scenes/scene_loader.h"
#include "tests/test_support.h"
#include "util/error.h"

namespace sdfbench {
namespace {

const char* kValidScene = R"({
  "meshes": {"ball": {"builtin": "sphere"}},
  "materials": {"red": {"albedo": [0.8, 0.1, 0.1]}, "floor": {"checker": {"size": 2, "albedo": [0.1, 0.1, 0.1]}}},
  "instances": [{"mesh": "ball", "material": "red", "translate": [0, 1, 0],
                 "rotate": {"axis": [0, 1, 0], "degrees": 30}, "scale": 2}],
  "lights": [{"type": "directional", "direction": [1, 2, 1]}, {"type": "point", "position": [0, 5, 0], "color": [1, 1, 1]}],
  "camera": {"position": [0, 2, 8], "look_at": [0, 1, 0], "fov_y": 40},
  "floor": {"height": 0, "material": "floor"},
  "render": {"width": 64, "height": 32}
})";

// Replaces the first occurrence of `from` in the valid scene.
std::string variant(const std::string& from, const std::string& to) {
  std::string s = kValidScene;
  const size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return s.replace(at, from.size(), to);
}

// Parses and returns the error message ("" if it parsed).
std::string error_of(const std::string& json) {
  try {
    parse_scene_json(json, "test_scene.json");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(SceneLoader, ParsesAValidDescriptor) {
  const Scene scene = parse_scene_json(kValidScene, "test_scene.json");
  ASSERT_EQ(scene.instances.size(), 1u);
  EXPECT_EQ(scene.meshes[0].triangle_count(), 768u);
  EXPECT_FLOAT_EQ(scene.instances[0].transform.scale, 2.0f);
  EXPECT_EQ(scene.lights.size(), 2u);
  EXPECT_EQ(scene.lights[1].kind, Light::Kind::Point);
  EXPECT_TRUE(scene.floor.enabled);
  EXPECT_EQ(scene.materials[scene.floor.material].name, "floor");
  EXPECT_EQ(scene.render.width, 64u);
}

TEST(SceneLoader, MalformedJsonNamesTheFile) {
  const std::string e = error_of(R"({"meshes": {)");
  EXPECT_NE(e.find("test_scene.json"), std::string::npos) << e;
  EXPECT_NE(e.find("malformed JSON"), std::string::npos) << e;
}

struct BadField {
  const char* from;
  const char* to;
  const char* field;    // must appear in the message
  const char* problem;  // must appear in the message
};

class SceneLoaderRejects : public testing::TestWithParam<BadField> {};

TEST_P(SceneLoaderRejects, WithFileFieldAndProblem) {
  const BadField& bad = GetParam();
  const std::string e = error_of(variant(bad.from, bad.to));
  ASSERT_FALSE(e.empty()) << "accepted: " << bad.to;
  EXPECT_NE(e.find("test_scene.json"), std::string::npos) << e;
  EXPECT_NE(e.find(bad.field), std::string::npos) << e;
  EXPECT_NE(e.find(bad.problem), std::string::npos) << e;
}

INSTANTIATE_TEST_SUITE_P(
    Descriptor, SceneLoaderRejects,
    testing::Values(
        BadField{"\"fov_y\": 40", "\"fov_y\": 40, \"postion\": [0,0,0]", "camera.postion", "unknown field"},
        BadField{"\"mesh\": \"ball\"", "\"mesh\": \"bal\"", "instances[0].mesh", "unknown mesh 'bal'"},
        BadField{"\"material\": \"red\"", "\"material\": \"blue\"", "instances[0].material", "unknown material"},
        BadField{"\"type\": \"directional\"", "\"type\": \"spot\"", "lights[0].type", "unknown light type"},
        BadField{"\"builtin\": \"sphere\"", "\"builtin\": \"cube\"", "meshes.ball.builtin", "unknown built-in mesh"},
        BadField{"\"builtin\": \"sphere\"", "\"file\": \"no_such_mesh.obj\"", "meshes.ball", "does not exist"},
        BadField{"\"scale\": 2", "\"scale\": -2", "instances[0].scale", "must be in"},
        BadField{"\"scale\": 2", "\"scale\": 0", "instances[0].scale", "must be in"},
        BadField{"\"scale\": 2", "\"scale\": [2, 1, 1]", "instances[0].scale", "expected a number"},
        BadField{"\"width\": 64", "\"width\": 0", "render.width", "must be in"},
        BadField{"\"height\": 32", "\"height\": -5", "render.height", "must be in"},
        BadField{"\"width\": 64", "\"width\": 64.5", "render.width", "expected an integer"},
        BadField{"\"albedo\": [0.8, 0.1, 0.1]", "\"albedo\": [0.8, -0.1, 0.1]", "materials.red.albedo", ">= 0"},
        BadField{"\"albedo\": [0.8, 0.1, 0.1]", "\"albedo\": [0.8, 0.1]", "materials.red.albedo", "3 numbers"},
        BadField{"\"look_at\": [0, 1, 0]", "\"look_at\": [0, 2, 8]", "camera.look_at", "equals its position"},
        BadField{"\"fov_y\": 40", "\"fov_y\": 40, \"up\": [0, 0, 0]", "camera.up", "zero or parallel"},
        BadField{"\"fov_y\": 40", "\"fov_y\": 40, \"up\": [0, -2, -16]", "camera.up", "zero or parallel"},
        BadField{"\"direction\": [1, 2, 1]", "\"direction\": [0, 0, 0]", "lights[0].direction", "must not be zero"},
        BadField{"\"instances\": [", "\"instances\": [], \"unused\": [", "unused", "unknown field"}),
    [](const testing::TestParamInfo<BadField>& info) { return "case" + std::to_string(info.index); });

TEST(SceneLoader, MaterialsKeepDeclarationOrder) {
  // "red" is declared before "floor": index 0 (the default) is red, not the alphabetically first.
  const Scene scene = parse_scene_json(kValidScene, "test_scene.json");
  EXPECT_EQ(scene.materials[0].name, "red");
  EXPECT_EQ(scene.materials[1].name, "floor");
}

TEST(SceneLoader, RejectsAnEmptyInstanceList) {
  std::string s = kValidScene;
  const size_t begin = s.find("\"instances\"");
  const size_t end = s.find("\"lights\"");
  s.replace(begin, end - begin, "\"instances\": [], ");
  const std::string e = error_of(s);
  EXPECT_NE(e.find("instances"), std::string::npos) << e;
  EXPECT_NE(e.find("at least one instance"), std::string::npos) << e;
}

TEST(SceneLoader, MeshFilesResolveRelativeToTheDescriptor) {
  test::TempDir dir;
  dir.write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const auto path = dir.write("scene.json", variant("\"builtin\": \"sphere\"", "\"file\": \"tri.obj\""));
  const Scene scene = load_scene_file(path);
  EXPECT_EQ(scene.meshes[0].triangle_count(), 1u);
}

TEST(SceneLoader, OutOfRangeObjIndexNamesFileFaceAndIndex) {
  test::TempDir dir;
  dir.write("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 7\n");
  const auto path = dir.write("scene.json", variant("\"builtin\": \"sphere\"", "\"file\": \"bad.obj\""));
  try {
    load_scene_file(path);
    FAIL() << "accepted an OBJ with an out-of-range index";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("bad.obj"), std::string::npos) << m;
    EXPECT_NE(m.find("meshes.ball"), std::string::npos) << m;
    EXPECT_TRUE(m.find("vertex index 7") != std::string::npos || m.find("index") != std::string::npos) << m;
  }
}

TEST(SceneLoader, MissingSceneFile) {
  EXPECT_THROW(load_scene_file("/nonexistent/scene.json"), Error);
}

}  // namespace
}  // namespace sdfbench
