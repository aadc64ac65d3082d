// Mesh files through assimp (scenes/mesh_file.*): PLY (ASCII and binary), OFF and glTF 2.0
// (.gltf with an external buffer, .glb) load with their node transforms; hostile files are one
// Error naming the file and the part at fault, before anything large is allocated; and the
// Khronos models Debian ships (assimp-testmodels) render with every backend as Embree does.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "harness/image_agreement.h"
#include "renderers/renderer.h"
#include "scenes/mesh.h"
#include "scenes/gltf_scene.h"
#include "scenes/mesh_file.h"
#include "scenes/scene_loader.h"
#include "tests/test_support.h"
#include "util/error.h"

namespace sdfbench {
namespace {

const std::filesystem::path kSeeds = data_dir().parent_path() / "tests/fuzz/mesh_file_seeds";
const std::filesystem::path kModels = "/usr/share/assimp/models";  // Debian's assimp-testmodels (install_deps.sh)

TEST(MeshFile, EachFormatLoadsWithItsNodeTransforms) {
  for (const char* file : {"cube.ply", "cube_binary.ply", "cube.off"}) {
    const Mesh mesh = load_mesh_file(kSeeds / file, "cube");
    EXPECT_EQ(mesh.triangle_count(), 12u) << file;
    EXPECT_EQ(mesh.bounds.extent(), glm::vec3(1.0f)) << file;
  }
  // Two nodes place one cube: at x + 2, and scaled by a half at the origin.
  for (const char* file : {"two_cubes.gltf", "two_cubes.glb"}) {
    const Mesh mesh = load_mesh_file(kSeeds / file, "cubes");
    EXPECT_EQ(mesh.triangle_count(), 24u) << file;
    EXPECT_EQ(mesh.bounds.min, glm::vec3(0.0f)) << file;
    EXPECT_EQ(mesh.bounds.max, glm::vec3(3.0f, 1.0f, 1.0f)) << file;
  }
  // The Khronos samples: an external .bin beside a .gltf, and a multi-node, multi-mesh .glb.
  ASSERT_TRUE(std::filesystem::exists(kModels)) << "assimp-testmodels is not installed (harness/scripts/install_deps.sh)";
  EXPECT_EQ(load_mesh_file(kModels / "glTF2/BoxTextured-glTF/BoxTextured.gltf", "box").triangle_count(), 12u);
  EXPECT_EQ(load_mesh_file(kModels / "glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb", "engine").triangle_count(),
            121496u);
  EXPECT_EQ(load_mesh_file(kModels / "PLY/Wuson.ply", "wuson").triangle_count(), 3732u);
  EXPECT_EQ(load_mesh_file(kModels / "OFF/Wuson.off", "wuson").triangle_count(), 3732u);
}

// The seed's text with `from` replaced by `to` (the test fails if `from` is not there).
std::string edited(const std::string& seed, const std::string& from, const std::string& to) {
  std::ifstream in(kSeeds / seed, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << seed << " has no '" << from << "'";
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

void expect_error(const std::filesystem::path& file, const std::string& part) {
  try {
    load_mesh_file(file, "hostile");
    ADD_FAILURE() << file << " loaded; expected an error naming '" << part << "'";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(file.string()), std::string::npos) << message;
    EXPECT_NE(message.find(part), std::string::npos) << "expected '" << part << "' in: " << message;
  }
}

TEST(MeshFile, HostileFilesAreErrorsNamingThePart) {
  const test::TempDir dir;
  const std::string cube_ply = edited("cube.ply", "", "");
  // PLY: a truncated body, huge declared counts, a list count past its type, a digit-led name.
  expect_error(dir.write("truncated.ply", cube_ply.substr(0, cube_ply.size() - 40)), "the file ends");
  expect_error(dir.write("huge.ply", edited("cube.ply", "element vertex 8", "element vertex 4294967295")), "declares 4294967295");
  expect_error(dir.write("list.ply", edited("cube.ply", "3 0 2 1", "300 0 2 1")), "list count '300'");
  expect_error(dir.write("name.ply", edited("cube.ply", "element vertex", "element 18446744073709551615vertex")),
               "element name");
  // A comment that Debian 13's assimp reads as a count (a 100 GB allocation there; the fuzz found it).
  expect_error(dir.write("comment.ply", edited("cube.ply", "comment a unit cube", "comment 4294967295 a unit cube")),
               "a comment that starts with a number");
  expect_error(dir.write("indented.ply", edited("cube.ply", "comment a unit cube", " comment 18446744073709551615a cube")),
               "a comment that starts with a number");
  // OFF: counts beyond the limit and beyond the file.
  expect_error(dir.write("huge.off", edited("cube.off", "8 12 0", "353535235358 6 0")), "declares 353535235358 vertices");
  expect_error(dir.write("short.off", edited("cube.off", "8 12 0", "8000 12000 0")), "truncated");
  // glTF: accessor counts beyond the buffer, indices out of range, views past their buffer, cycles
  // and shared children in the node graph, huge counts, buffers outside the folder, a cut .glb.
  expect_error(dir.write("count.gltf", edited("two_cubes.gltf", "\"count\": 8", "\"count\": 80")),
               "accessors[0]: 80 elements");
  expect_error(dir.write("index.gltf", edited("two_cubes.gltf", "\"indices\": 1", "\"indices\": 7")),
               "meshes[0].primitives[0].indices: 7 is out of range");
  expect_error(dir.write("view.gltf", edited("two_cubes.gltf", "\"byteLength\": 72", "\"byteLength\": 720")),
               "bufferViews[1]");
  expect_error(dir.write("cycle.gltf", edited("two_cubes.gltf", "\"mesh\": 0,", "\"children\": [0], \"mesh\": 0,")),
               "a cycle in the node graph");
  expect_error(dir.write("shared.gltf", edited("two_cubes.gltf", "\"children\": [\n    1,\n    2\n   ]",
                                               "\"children\": [\n    1,\n    1\n   ]")),
               "already has a parent");
  expect_error(dir.write("huge.gltf", edited("two_cubes.gltf", "\"count\": 36", "\"count\": 4294967295")),
               "accessors[1].count: 4294967295 is outside");
  expect_error(dir.write("escape.gltf", edited("two_cubes.gltf", "data:application/octet-stream;base64,", "../x.bin#")),
               "buffers[0].uri");
  expect_error(dir.write("absolute.gltf", edited("two_cubes.gltf", "data:application/octet-stream;base64,", "/etc/passwd#")),
               "buffers[0].uri");
  const std::string glb = edited("two_cubes.glb", "", "");
  expect_error(dir.write("cut.glb", glb.substr(0, glb.size() / 2)), "truncated");
  expect_error(dir.write("mesh.stl", "solid x\n"), "is not a mesh file sdfbench reads");
  // assimp's own hostile glTF samples.
  ASSERT_TRUE(std::filesystem::exists(kModels)) << "assimp-testmodels is not installed (harness/scripts/install_deps.sh)";
  const std::filesystem::path gltf = kModels / "glTF2";
  expect_error(gltf / "RecursiveNodes/RecursiveNodes.gltf", "a cycle in the node graph");
  // (assimp 5.2 drops the face, which the reader counts; later versions may refuse it themselves)
  expect_error(gltf / "IndexOutOfRange/IndexOutOfRange.gltf", "out of range");
  expect_error(gltf / "IncorrectVertexArrays/Cube.gltf", "bufferViews[2]: bytes 504 + 432 pass the end of buffers[0]");
  expect_error(gltf / "BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb", "inite");  // "not finite" or assimp's "infinite"
  expect_error(gltf / "MissingBin/BoxTextured.gltf", "BoxTextured0.bin");
  expect_error(gltf / "TestNoRootNode/NoScene.gltf", "scene: 0 is out of range (0 scenes)");
}

TEST(MeshFile, SceneCoordinatesAndTheCommandLine) {
  const test::TempDir dir;
  dir.write("far.ply", edited("cube.ply", "1 1 1\n", "1e30 1 1\n"));
  dir.write("bad.ply", edited("cube.ply", "element vertex 8", "element vertex 9"));
  const std::string scene = R"({"meshes": {"m": {"file": "FILE"}}, "instances": [{"mesh": "m"}],
    "lights": [{"type": "directional", "direction": [0, 1, 0]}],
    "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov_y": 45}})";
  const auto with = [&](const std::string& file) {
    std::string s = scene;
    s.replace(s.find("FILE"), 4, file);
    return s;
  };
  // 1e30 is a finite float, so the file loads; the scene's coordinate limit names the mesh.
  try {
    load_scene_file(dir.write("far.json", with("far.ply")).string());
    ADD_FAILURE() << "a mesh at 1e30 was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("meshes.m"), std::string::npos) << e.what();
  }
  EXPECT_EQ(load_scene_file(dir.write("ok.json", with(kSeeds.string() + "/cube.off")).string()).triangle_count(), 12u);
  // On the command line: one error line, exit 1.
  const test::CommandResult r =
      test::run_sdfbench("render --scene " + dir.write("bad.json", with("bad.ply")).string() + " --backend embree --size 8x8 --frames 1");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_EQ(r.output.rfind("sdfbench: error: ", 0), 0u) << r.output;
  EXPECT_EQ(r.output.find('\n'), r.output.size() - 1) << r.output;
  EXPECT_NE(r.output.find("bad.ply"), std::string::npos) << r.output;
}

// The Khronos models (a multi-node, multi-mesh engine, the textured box with its external
// buffer and image, textured) and the PLY and OFF scans, side by side, each scaled to a unit: every backend draws
// what Embree draws, primary and shadow.
Scene khronos_scene() {
  Scene scene;
  scene.name = "khronos models";
  scene.materials.push_back(Material{.name = "grey", .albedo = glm::vec3(0.7f)});
  scene.lights.push_back(Light{.direction = glm::normalize(glm::vec3(0.4f, 1.0f, 0.3f))});
  // The textured box comes as its glTF scene has it: its base colour texture on its uv.
  Scene box = load_gltf_scene(kModels / "glTF2/BoxTextured-glTF/BoxTextured.gltf");
  scene.materials.push_back(box.materials.at(box.instances.at(0).material));
  scene.textures = box.textures;
  scene.texels = box.texels;
  const char* files[] = {"glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb", "glTF2/BoxTextured-glTF/BoxTextured.gltf",
                         "PLY/Wuson.ply", "OFF/Wuson.off"};
  float x = -3.3f;
  for (const char* file : files) {
    const bool textured = std::string(file).find("BoxTextured") != std::string::npos;
    Mesh mesh = textured ? box.meshes.at(0) : load_mesh_file(kModels / file, std::filesystem::path(file).stem().string());
    const glm::vec3 e = mesh.bounds.extent();
    Instance instance{.mesh = static_cast<uint32_t>(scene.meshes.size()), .material = textured ? 1u : 0u};
    instance.transform.scale = 2.0f / std::max({e.x, e.y, e.z});
    instance.transform.translation = glm::vec3(x, 0.0f, 0.0f) - instance.transform.scale * mesh.bounds.center();
    instance.transform.rotation = glm::angleAxis(0.6f, glm::normalize(glm::vec3(1.0f, 1.0f, 0.0f)));
    scene.meshes.push_back(std::move(mesh));
    scene.instances.push_back(instance);
    x += 2.2f;
  }
  scene.camera = Camera{.position = {0.0f, 0.5f, 4.6f}, .look_at = {0.0f, 0.0f, 0.0f}, .fov_y_degrees = 45.0f};
  return scene;
}

// --scene FILE.gltf|.glb: nodes become instances of shared meshes, the file's camera is the view
// (else a framing), glTF materials map to the shading program's (scenes/README.md, "glTF scenes").
TEST(GltfScene, NodesBecomeInstancesOfSharedMeshes) {
  const Scene scene = load_gltf_scene(kSeeds / "two_cubes.gltf");
  ASSERT_EQ(scene.meshes.size(), 1u);
  EXPECT_EQ(scene.meshes[0].triangle_count(), 12u);
  ASSERT_EQ(scene.instances.size(), 2u);
  EXPECT_EQ(scene.instances[0].transform.translation, glm::vec3(2, 0, 0));
  EXPECT_FLOAT_EQ(scene.instances[0].transform.scale, 1.0f);
  EXPECT_FLOAT_EQ(scene.instances[1].transform.scale, 0.5f);
  // No camera in the file: a framing that looks at the box's centre from outside it.
  EXPECT_EQ(scene.camera.look_at, scene.bounds().center());
  EXPECT_GT(glm::length(scene.camera.position - scene.camera.look_at), glm::length(scene.bounds().extent()));
  EXPECT_EQ(scene.lights.size(), 1u);  // the default sun
}

TEST(GltfScene, CameraMaterialsAndNonUniformScale) {
  const test::TempDir dir;
  nlohmann::json doc = nlohmann::json::parse(edited("two_cubes.gltf", "", ""));
  doc["cameras"] = R"([{"type": "perspective", "perspective": {"yfov": 0.5, "znear": 0.1}}])"_json;
  doc["materials"] = R"([{"pbrMetallicRoughness": {"baseColorFactor": [1, 0, 0, 1], "metallicFactor": 1,
                                                   "roughnessFactor": 0}}])"_json;
  doc["meshes"][0]["primitives"][0]["material"] = 0;
  doc["nodes"][2]["scale"] = {1, 2, 1};
  doc["nodes"].push_back(R"({"camera": 0, "translation": [0, 0, 10]})"_json);  // node 3, a root
  doc["scenes"][0]["nodes"] = {3, 0};
  const Scene scene = load_gltf_scene(dir.write("scene.gltf", doc.dump()));
  EXPECT_EQ(scene.camera.position, glm::vec3(0, 0, 10));
  EXPECT_EQ(scene.camera.look_at, glm::vec3(0, 0, 9));
  EXPECT_NEAR(scene.camera.fov_y_degrees, 0.5 * 180 / 3.14159265, 1e-3);
  ASSERT_FALSE(scene.instances.empty());
  const Material& material = scene.materials.at(scene.instances[0].material);
  EXPECT_EQ(material.albedo, glm::vec3(1, 0, 0));
  EXPECT_FLOAT_EQ(material.reflectance, 1.0f);
  // The node scaled (1, 2, 1) is baked into a mesh of its own; the other stays an instance.
  ASSERT_EQ(scene.meshes.size(), 2u);
  EXPECT_EQ(scene.meshes[1].bounds.extent(), glm::vec3(1, 2, 1));
  ASSERT_EQ(scene.instances.size(), 2u);
  EXPECT_EQ(scene.instances[1].mesh, 1u);
  EXPECT_FLOAT_EQ(scene.instances[1].transform.scale, 1.0f);
}

// The base colour texture on the mesh's texture coordinates: the same from an external image, a
// .glb and a data URI; the uv table holds the file's coordinates (v up, as assimp gives them),
// and the texture shows in the image.
TEST(GltfScene, BaseColourTextureOnTheMeshUv) {
  ASSERT_TRUE(std::filesystem::exists(kModels)) << "assimp-testmodels is not installed (harness/scripts/install_deps.sh)";
  const std::filesystem::path box = kModels / "glTF2/BoxTextured-glTF/BoxTextured.gltf";
  const Scene scene = load_gltf_scene(box);
  ASSERT_EQ(scene.instances.size(), 1u);
  const Material& material = scene.materials.at(scene.instances[0].material);
  ASSERT_EQ(scene.textures.size(), 1u);
  EXPECT_EQ(material.texture, 0u);
  EXPECT_EQ(scene.textures[0].width, 211u);  // CesiumLogoFlat.png
  EXPECT_EQ(scene.textures[0].height, 211u);
  ASSERT_EQ(material.triangle_uvs, 211u * 211u);  // after the image's texels, two per triangle
  ASSERT_EQ(scene.texels.size(), 211u * 211u + 2u * 12u);
  // The first face, vertices 0, 1, 2: the file's uv (6, 0), (5, 0), (6, 1) with v flipped.
  EXPECT_EQ(scene.texels[material.triangle_uvs], glm::vec4(6, 1, 5, 1));
  EXPECT_NEAR(scene.texels[material.triangle_uvs + 1].x, 6.0f, 1e-6f);
  EXPECT_NEAR(scene.texels[material.triangle_uvs + 1].y, 0.0f, 1e-6f);
  for (const char* other : {"BoxTextured-glTF-Binary/BoxTextured.glb", "BoxTextured-glTF-Embedded/BoxTextured.gltf"}) {
    const Scene same = load_gltf_scene(kModels / "glTF2" / other);
    EXPECT_EQ(same.texels, scene.texels) << other;
  }
  // A known answer: the world's +z face (the mesh's -y face, turned by the root node) seen head on
  // shows the logo mirrored left to right (its u runs from 1 at x = -0.5 to 0 at x = 0.5) and
  // upright; the sun, the sky and a hill at their places in the image.
  {
    Scene head_on = scene;
    head_on.camera = Camera{.position = {0, 0, 3}, .look_at = {0, 0, 0}, .fov_y_degrees = 24.0f};
    const uint32_t side = 100;
    const FrameImages image = test::render_frame("embree", head_on, RenderMode::Primary, side, side);
    const auto at = [&](float u, float v) {  // the pixel showing the image's point (u, v), from its top left
      const float tan_half = std::tan(glm::radians(12.0f)), x = 0.5f - u, y = 0.5f - v;
      const auto px = uint32_t((x / (2.5f * tan_half) + 1.0f) / 2.0f * side), py = uint32_t((1.0f - y / (2.5f * tan_half)) / 2.0f * side);
      return glm::vec3(image.color.at(py * side + px));
    };
    const glm::vec3 sun = at(138.0f / 211, 60.0f / 211), sky = at(0.3f, 0.3f), hill = at(0.5f, 0.85f);
    EXPECT_LT(std::abs(sun.x - sun.z), 0.05f) << "white sun";
    EXPECT_GT(sun.x, sky.x + 0.1f);
    EXPECT_GT(sky.z, sky.x + 0.1f) << "blue sky";
    EXPECT_GT(hill.y, hill.z + 0.1f) << "green hill";
  }
  // Drawn: the box's pixels take many colours (the logo), against a handful without the texture.
  Scene plain = scene;
  plain.materials.at(scene.instances[0].material).texture = Material::kNoTexture;
  const auto colours = [](const Scene& s) {
    const FrameImages image = test::render_frame("embree", s, RenderMode::Primary, 96, 72);
    std::set<std::tuple<int, int, int>> seen;
    for (size_t i = 0; i < image.color.size(); ++i)
      if (image.instance_id[i] == 0)
        seen.emplace(int(image.color[i].x * 16), int(image.color[i].y * 16), int(image.color[i].z * 16));
    return seen.size();
  };
  EXPECT_GT(colours(scene), 3 * colours(plain));
  // Hostile: an image outside the folder, one that declares 8000 x 8000, texture coordinates
  // that are not finite.
  const test::TempDir dir;
  std::filesystem::copy_file(box.parent_path() / "BoxTextured0.bin", dir.path() / "BoxTextured0.bin");
  const std::string text = [&] {
    std::ifstream in(box, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  }();
  const auto with_image = [&](const std::string& uri) {
    std::string t = text;
    t.replace(t.find("CesiumLogoFlat.png"), std::string("CesiumLogoFlat.png").size(), uri);
    return t;
  };
  const auto expect_scene_error = [](const std::filesystem::path& file, const std::string& part) {
    try {
      load_gltf_scene(file);
      ADD_FAILURE() << file << " loaded; expected an error naming '" << part << "'";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << "expected '" << part << "' in: " << e.what();
      EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
    }
  };
  expect_scene_error(dir.write("escape.gltf", with_image("../CesiumLogoFlat.png")),
                     "images[0].uri: '../CesiumLogoFlat.png' is not a plain relative path");
  const unsigned char header[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13, 'I', 'H', 'D', 'R',
                                  0, 0, 0x1f, 0x40, 0, 0, 0x1f, 0x40, 8, 2, 0, 0, 0, 0, 0, 0, 0};  // 8000 x 8000 RGB
  const std::string huge_png(reinterpret_cast<const char*>(header), sizeof header);
  dir.write("huge.png", huge_png);
  expect_scene_error(dir.write("huge.gltf", with_image("huge.png")), "material 'Texture': base colour texture 'huge.png'");  // (the size or libstb's refusal, by version)
  const nlohmann::json doc = nlohmann::json::parse(text);
  const nlohmann::json& uv = doc["accessors"][doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"].get<size_t>()];
  const size_t at = doc["bufferViews"][uv["bufferView"].get<size_t>()].value("byteOffset", 0u) + uv.value("byteOffset", 0u);
  for (const float bad : {std::nanf(""), 1e30f}) {
    const test::TempDir copy;
    std::filesystem::copy_file(box, copy.path() / "BoxTextured.gltf");
    std::filesystem::copy_file(box.parent_path() / "CesiumLogoFlat.png", copy.path() / "CesiumLogoFlat.png");
    std::ifstream in(box.parent_path() / "BoxTextured0.bin", std::ios::binary);
    std::string bin((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::memcpy(bin.data() + at + 4, &bad, sizeof bad);  // vertex 0's v
    copy.write("BoxTextured0.bin", bin);
    expect_scene_error(copy.path() / "BoxTextured.gltf", "vertex 0: its texture coordinate is not a finite number within +-1000");
  }
}

TEST(GltfScene, TheKhronosEngineRendersAsEmbreeDoesOnTheCommandLine) {
  ASSERT_TRUE(std::filesystem::exists(kModels)) << "assimp-testmodels is not installed (harness/scripts/install_deps.sh)";
  const std::filesystem::path engine = kModels / "glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";
  const Scene scene = load_gltf_scene(engine);
  EXPECT_LT(scene.meshes.size(), scene.instances.size()) << "meshes used by several nodes are shared";
  // The instances' transforms (decomposed node matrices) put the parts where the merged mesh
  // (the full matrices applied to the vertices) has them.
  const Aabb merged = load_mesh_file(engine, "engine").bounds;
  Aabb placed;
  for (const Instance& instance : scene.instances)
    for (const glm::vec3& p : scene.meshes[instance.mesh].positions)
      placed.extend(glm::vec3(instance.transform.object_to_world() * glm::vec4(p, 1.0f)));
  const float tolerance = 1e-4f * glm::length(merged.extent());
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_NEAR(placed.min[axis], merged.min[axis], tolerance) << axis;
    EXPECT_NEAR(placed.max[axis], merged.max[axis], tolerance) << axis;
  }
  for (const char* backend : {"bvh", "vk-rt"}) {  // (every backend draws the engine in MeshFileBackends)
    const test::CommandResult r = test::run_sdfbench("compare --scene " + engine.string() + " --backends " + backend +
                                                     " --size 96x54");
    EXPECT_EQ(r.exit_code, 0) << backend << ": " << r.output;
  }
  const test::CommandResult bad = test::run_sdfbench("render --scene " + (kModels / "glTF2/RecursiveNodes/RecursiveNodes.gltf").string() +
                                                     " --backend embree --size 8x8");
  EXPECT_EQ(bad.exit_code, 1) << bad.output;
  EXPECT_EQ(bad.output.rfind("sdfbench: error: glTF scene '", 0), 0u) << bad.output;
  EXPECT_EQ(bad.output.find('\n'), bad.output.size() - 1) << bad.output;
}

class MeshFileBackends : public ::testing::TestWithParam<std::string> {};

TEST_P(MeshFileBackends, DrawWhatEmbreeDraws) {
  ASSERT_TRUE(std::filesystem::exists(kModels)) << "assimp-testmodels is not installed (harness/scripts/install_deps.sh)";
  const Scene scene = khronos_scene();
  // Each of the four models shows (at least 1 % of the frame): agreement on sky proves nothing.
  const FrameImages reference = test::render_frame("embree", scene, RenderMode::Primary, 128, 48);
  std::vector<size_t> pixels(scene.instances.size(), 0);
  for (uint32_t id : reference.instance_id)
    if (id < pixels.size()) ++pixels[id];
  for (size_t i = 0; i < pixels.size(); ++i) EXPECT_GE(pixels[i], 128u * 48u / 100u) << scene.meshes[i].name;
  for (RenderMode mode : {RenderMode::Primary, RenderMode::Shadow})
    test::expect_agrees_with_embree(GetParam(), scene, mode, 128, 48);
}

INSTANTIATE_TEST_SUITE_P(EveryBackend, MeshFileBackends, ::testing::ValuesIn(test::backends_but_the_reference()),
                         [](const auto& info) { return test::backend_test_name(info.param); });

}  // namespace
}  // namespace sdfbench
