// Issue 11's limits: inputs whose size, depth or scale would crash, run away or silently change
// the picture get one short line naming what and the limit, exit 1, in bounded time; a far
// instance changes nothing one sees.
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "renderers/backend_registry.h"
#include "renderers/bvh/bvh_renderer.h"
#include "renderers/frame_params.h"
#include "scenes/scene_loader.h"
#include "scenes/scene_source.h"
#include "tests/test_support.h"
#include "util/error.h"

namespace sdfbench {
namespace {

test::CommandResult run_limited(const std::string& args, int seconds = 30) {
  return test::run_shell("exec " + std::string(SDFBENCH_BINARY) + " " + args, seconds);
}

// The last line of the output (the error line, after any progress lines).
std::string last_line(const std::string& output) {
  std::string text = output;
  while (!text.empty() && text.back() == '\n') text.pop_back();
  const size_t nl = text.rfind('\n');
  return nl == std::string::npos ? text : text.substr(nl + 1);
}

// Exit 1, one "sdfbench: error:" line no longer than `max_chars`, containing every word.
void expect_short_error(const std::string& args, const std::vector<std::string>& words, size_t max_chars = 400,
                        int seconds = 30) {
  const test::CommandResult r = run_limited(args, seconds);
  const std::string line = last_line(r.output);
  EXPECT_EQ(r.exit_code, 1) << args << "\n" << r.output.substr(0, 2000);
  EXPECT_EQ(line.rfind("sdfbench: error: ", 0), 0u) << args << "\n" << r.output.substr(0, 2000);
  EXPECT_LE(line.size(), max_chars) << args << "\n" << line.substr(0, 2000);
  for (const std::string& w : words) EXPECT_NE(line.find(w), std::string::npos) << args << ": no '" << w << "' in\n" << line.substr(0, 2000);
}

// {"type": "union", "children": [<levels deeper>, sphere]} nested `levels` deep: on the left,
// which a postfix stack evaluates in 2 slots (only the nesting is too deep).
std::string nested_csg_scene(int levels, bool right) {
  const std::string sphere = R"({"type": "sphere", "radius": 1})";
  std::string shape = sphere;
  for (int i = 0; i < levels; ++i)
    shape = right ? R"({"type": "union", "children": [)" + sphere + ", " + shape + "]}"
                  : R"({"type": "union", "children": [)" + shape + ", " + sphere + "]}";
  return R"({"materials": {"m": {"albedo": [0.8, 0.8, 0.8]}},
  "implicits": [{"material": "m", "shape": )" + shape + R"(}],
  "lights": [{"type": "directional", "direction": [0, 1, 0]}],
  "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]}})";
}

TEST(Limits, DeeplyNestedCsgIsAShortErrorNotACrash) {
  const test::TempDir dir;
  for (const bool right : {false, true}) {
    const std::string scene = dir.write(right ? "right.json" : "left.json", nested_csg_scene(20000, right)).string();
    expect_short_error("render --backend embree --frames 1 --warmup 0 --size 8x8 --scene " + scene,
                       {"nested more than 32", "implicits[0].shape", "characters)"}, 400, 20);
  }
  // Within the limits it still loads: 20 levels on the left are 41 nodes, an evaluation stack of 2.
  const std::string ok = dir.write("ok.json", nested_csg_scene(20, false)).string();
  const test::CommandResult r = run_limited("render --backend embree --frames 1 --warmup 0 --size 8x8 --scene " + ok, 30);
  EXPECT_EQ(r.exit_code, 0) << r.output;
}

TEST(Limits, RunawayOctreeStopsAtTheMemoryCap) {
  expect_short_error("build --scene thesis:sphere:10 --octree-depth 16 --octree-min-size 1e-6 --max-structure-mb 16",
                     {"octrees need more than 16 MiB", "--max-structure-mb 16", "--octree-depth", "--octree-min-size"},
                     400, 30);
  // The cap is a flag with a stated range.
  expect_short_error("build --scene thesis:sphere:1 --max-structure-mb 0", {"--max-structure-mb"});
}

TEST(Limits, MeshGridListsStopAtTheMemoryCap) {
  expect_short_error("build --scene thesis:sphere:1 --cells-per-extent 256 --max-structure-mb 1",
                     {"mesh 'sphere'", "cell lists need more than 1.0 MiB", "--max-structure-mb"}, 400, 30);
}

// The shape of the far-instance scenes: one sphere and an implicit box with a hole over a floor,
// lit from the side (their shadows in view), and, when `far` is given, a second sphere that far
// out along x (out of view).
std::string far_scene(const std::string& far) {
  std::string s = R"({"meshes": {"ball": {"builtin": "sphere"}},
  "materials": {"grey": {"albedo": [0.8, 0.8, 0.8]}, "floor": {"albedo": [0.9, 0.9, 0.9]}},
  "instances": [{"mesh": "ball", "material": "grey", "translate": [0.6, 1, 0], "scale": 0.8})";
  if (!far.empty()) s += R"(, {"mesh": "ball", "material": "grey", "translate": [)" + far + ", 0, 0]}";
  s += R"(],
  "implicits": [{"material": "grey", "translate": [-1.2, 0.6, 0.3],
    "shape": {"type": "subtraction", "children": [{"type": "box", "half_extents": [0.5, 0.5, 0.5]},
                                                 {"type": "sphere", "radius": 0.62}]}}],
  "lights": [{"type": "directional", "direction": [0.6, 1.0, 0.3]}],
  "camera": {"position": [0, 2.5, 6], "look_at": [0, 0.6, 0], "fov_y": 40},
  "floor": {"height": 0, "material": "floor"},
  "render": {"width": 96, "height": 54}})";
  return s;
}

std::vector<float> read_png(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) return {};
  const OIIO::ImageSpec& spec = in->spec();
  std::vector<float> pixels(static_cast<size_t>(spec.width) * spec.height * spec.nchannels);
  in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data());
  return pixels;
}

TEST(Limits, FarInstanceChangesNothingInView) {
  const test::TempDir dir;
  const std::string near = dir.write("near.json", far_scene("")).string();
  const std::string far = dir.write("far.json", far_scene("1e6")).string();
  std::filesystem::create_directories(dir.path() / "near");
  std::filesystem::create_directories(dir.path() / "far");
  // Hash cell 1000: the default octree over the 1e6 of empty space between the two would pass
  // the memory cap (which says so); the picture does not depend on it.
  const std::string backends = " --backends embree,tri-aabb,sdf-hash,sdf-octree,sdf-cpu --mode shadow --hash-cell 1000";
  for (const std::string& which : {std::string("near"), std::string("far")}) {
    const test::CommandResult r = run_limited("compare --scene " + (dir.path() / (which + ".json")).string() + backends + " --out-dir " +
                                  (dir.path() / which).string(),
                              120);
    EXPECT_EQ(r.exit_code, 0) << which << ": every backend agrees with Embree\n" << r.output;
  }
  // The scale the limits derive from ignores the far sphere.
  EXPECT_EQ(scene_scale(load_scene_file(far)), scene_scale(load_scene_file(near)));
  for (const char* backend : {"embree", "tri-aabb", "sdf-hash", "sdf-octree", "sdf-cpu"}) {
    const std::vector<float> a = read_png((dir.path() / "near" / (std::string(backend) + ".png")).string());
    const std::vector<float> b = read_png((dir.path() / "far" / (std::string(backend) + ".png")).string());
    ASSERT_FALSE(a.empty()) << backend;
    ASSERT_EQ(a.size(), b.size()) << backend;
    size_t differ = 0;
    for (size_t i = 0; i < a.size(); ++i) differ += std::abs(a[i] - b[i]) > 0.02f;
    EXPECT_EQ(differ, 0u) << backend << ": the far instance changed the picture in view (shadows, the implicit's hole)";
  }
}

TEST(Limits, HugeSceneExtentGivesRealCellCounts) {
  const test::TempDir dir;
  const std::string scene = dir.write("e9.json", far_scene("9.9e8")).string();
  expect_short_error("build --scene " + scene, {"--hash-cell 10 gives 9.9e+07 x 1 x 1 = 9.9e+07 cells", "limit of 67108864"});
  expect_short_error("build --scene " + scene + " --hash-cell 1e-6", {"--hash-cell 1e-06 gives 9.9e+14 x", "cells"});
  expect_short_error("build --scene " + scene + " --hash-cell 1e-30", {"--hash-cell: expected a number in [1e-06, 1e+09], got '1e-30'"});
}

// One triangle with corners at +-c (as written) on every axis it spans.
std::string triangle_obj(const std::string& c) {
  return "v -" + c + " -" + c + " 0\nv " + c + " -" + c + " 0\nv 0 " + c + " " + c + "\nf 1 2 3\n";
}

// `mesh_file` once, `transform` its JSON transform fields, seen from `camera` units away along z.
std::string one_mesh_scene(const std::string& mesh_file, const std::string& transform, const std::string& camera) {
  return R"({"meshes": {"tri": {"file": ")" + mesh_file + R"("}},
  "instances": [{"mesh": "tri")" + (transform.empty() ? "" : ", " + transform) + R"(}],
  "lights": [{"type": "directional", "direction": [0.3, 1, 0.5]}],
  "camera": {"position": [0, 0, )" + camera + R"(], "look_at": [0, 0, 0]}})";
}

// Issue 27: coordinates whose squares overflow float made the bvh kernel loop for ever. Every
// backend in every mode renders such a scene or refuses it with one line, in bounded time; beyond
// the coordinate limit (1e9), always refused, naming the mesh file or the instance.
TEST(Limits, HugeCoordinatesRenderOrAreRefusedByEveryBackend) {
  const test::TempDir dir;
  struct Case {
    std::string name, scene;
    std::vector<std::string> words;  // in the refusal; empty: within the limit, a render or a clean error
  };
  std::vector<Case> cases;
  for (const std::string c : {"1e19", "1e30", "3e38"}) {
    const std::string obj = dir.write("tri" + c + ".obj", triangle_obj(c)).string();
    cases.push_back({c, one_mesh_scene(obj, "", "5"), {"meshes.tri", "tri" + c + ".obj", "limit of 1e+09"}});
  }
  const std::string small = dir.write("small.obj", triangle_obj("1e4")).string();
  cases.push_back({"scale", one_mesh_scene(small, R"("scale": 1e6)", "1e8"), {"instances[0]", "limit of 1e+09"}});
  cases.push_back({"translate", one_mesh_scene(small, R"("translate": [1e30, 0, 0])", "1e8"), {"instances[0]", "limit of 1e+09"}});
  const std::string edge = dir.write("edge.obj", triangle_obj("1e9")).string();
  cases.push_back({"at the limit", one_mesh_scene(edge, "", "1e9"), {}});
  for (const Case& c : cases) {
    const std::string scene = dir.write("scene.json", c.scene).string();
    for (const char* backend : {"embree", "tri-aabb", "bvh", "vk-rt", "sdf-hash", "sdf-octree", "sdf-cpu"})
      // Refused scenes in every mode; the scene at the limit, which renders, in whitted mode only
      // (its closest and any-hit queries are the other modes'; each render compiles kernels).
      for (const char* mode : {"primary", "shadow", "whitted"}) {
        if (c.words.empty() && std::string(mode) != "whitted") continue;
        const std::string args = "render --size 32x18 --frames 1 --warmup 0 --backend " + std::string(backend) + " --mode " +
                                 mode + " --scene " + scene;
        if (!c.words.empty()) {
          expect_short_error(args, c.words, 400, 60);
          continue;
        }
        // At the limit every backend renders: the SDF backends with a hash cell sized for a scene
        // 2e9 across (their default cell is refused by the hash's cell count, naming --hash-cell).
        const bool sdf = std::string(backend).rfind("sdf-", 0) == 0;
        const test::CommandResult r = run_limited(args + (sdf ? " --hash-cell 1e8" : ""), 120);
        EXPECT_EQ(r.exit_code, 0) << c.name << ": " << args << "\n" << r.output;
        EXPECT_NE(last_line(r.output).find("Mrays/s"), std::string::npos) << c.name << ": " << args << "\n" << r.output;
        if (sdf) {
          const test::CommandResult refused = run_limited(args, 120);
          EXPECT_EQ(refused.exit_code, 1) << args << "\n" << refused.output;
          EXPECT_NE(refused.output.find("sdfbench: error: --hash-cell"), std::string::npos) << args << "\n" << refused.output;
        }
      }
  }
}

// A mesh checked on its own (check-sdf --mesh FILE) is held to the same limit as a scene's.
TEST(Limits, CheckSdfMeshFileHasTheCoordinateLimit) {
  const test::TempDir dir;
  const std::string obj = dir.write("tri1e19.obj", triangle_obj("1e19")).string();
  expect_short_error("check-sdf --samples 10 --mesh " + obj, {"--mesh '" + obj + "'", "mesh 'tri1e19'", "limit of 1e+09"}, 400, 60);
}

TEST(Limits, CoordinateLimitCoversTheCameraLightsAndFloor) {
  const test::TempDir dir;
  const std::string small = dir.write("small.obj", triangle_obj("1")).string();
  std::string scene = one_mesh_scene(small, "", "2e9");
  EXPECT_THROW(parse_scene_json(scene, dir.path() / "camera.json"), Error);
  scene = one_mesh_scene(small, "", "5");
  scene.replace(scene.find(R"("lights": [)"), 11, R"("lights": [{"type": "point", "position": [0, -1e10, 0]}, )");
  try {
    parse_scene_json(scene, dir.path() / "light.json");
    ADD_FAILURE() << "a point light at 1e10 was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("lights[0].position"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(parse_scene_json(one_mesh_scene(small, R"("translate": [9e8, 0, 0])", "5"), dir.path() / "ok.json"));
  scene = one_mesh_scene(small, "", "5");
  scene.replace(scene.rfind('}'), 1, R"(, "floor": {"height": -2e9}})");
  try {
    parse_scene_json(scene, dir.path() / "floor.json");
    ADD_FAILURE() << "a floor at -2e9 was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("floor"), std::string::npos) << e.what();
  }
  scene = one_mesh_scene(small, "", "5");
  scene.replace(scene.rfind('}'), 1, R"(, "floor": {"height": -9e8}})");
  EXPECT_NO_THROW(parse_scene_json(scene, dir.path() / "floor_ok.json"));
}

// The traversals' own iteration bounds report cut pixels (a TRUNCATED row, render and compare
// fail), never a hang or a silent miss: a bvh traversal may make 2 node visits (the bunnies' BVHs
// need more), an octree descent none (sdf-octree's thesis octrees are deeper).
TEST(Limits, TraversalIterationBoundsReportCutPixels) {
  const Scene scene = load_scene("thesis:bunny:10");
  const FrameRequest request{64, 36, RenderMode::Shadow, false};
  const std::unique_ptr<Renderer> created = create_renderer("bvh", BackendOptions{});  // its parameters resolved
  auto& bvh = dynamic_cast<BvhRenderer&>(*created);
  bvh.prepare(scene);
  EXPECT_EQ(bvh.render(request).truncated_pixels, 0u);
  bvh.limit_visits_for_testing(2);
  bvh.prepare(scene);
  const FrameResult cut = bvh.render(request);
  EXPECT_GT(cut.bound_pixels, 0u);
  EXPECT_EQ(cut.bound_pixels, cut.truncated_pixels);
  EXPECT_NE(truncation_error("bvh", cut).find("hard bound"), std::string::npos) << truncation_error("bvh", cut);

  BackendOptions options;
  const FrameResult whole = [&] {
    auto octree = create_renderer("sdf-octree", options);
    octree->prepare(scene);
    return octree->render(request);
  }();
  EXPECT_EQ(whole.truncated_pixels, 0u);
  options.kernel_defines = "#define SDF_MAX_OCTREE_DEPTH 0u\n";
  auto shallow = create_renderer("sdf-octree", options);
  shallow->prepare(scene);
  const FrameResult descent = shallow->render(request);
  EXPECT_GT(descent.bound_pixels, 0u);
  EXPECT_NE(truncation_error("sdf-octree", descent).find("hard bound"), std::string::npos);
}

TEST(Limits, NumericFlagsHaveSaneRangesAndShortMessages) {
  const std::string render = "render --backend sdf-cpu --scene thesis:sphere:1 --size 16x9 --frames 1 --warmup 0";
  expect_short_error(render + " --hash-cell 0", {"--hash-cell", "[1e-06, 1e+09]"}, 200);
  expect_short_error(render + " --octree-min-size -1", {"--octree-min-size"}, 200);
  expect_short_error(render + " --hit-epsilon 1", {"--hit-epsilon", "0.01"}, 200);
  expect_short_error(render + " --hit-epsilon nan", {"--hit-epsilon"}, 200);
  expect_short_error(render + " --hit-footprint 5", {"--hit-footprint"}, 200);
  expect_short_error(render + " --mesh-cell inf", {"--mesh-cell"}, 200);
  expect_short_error("compare --backends embree --scene thesis:sphere:1 --size 16x9 --min-psnr nan", {"--min-psnr"}, 200);
  expect_short_error("compare --backends embree --scene thesis:sphere:1 --size 16x9 --min-hit 101", {"--min-hit"}, 200);
  expect_short_error("render --backend embree --scene thesis:sphere:1 --size 18446744073709551615x10",
                     {"--size", "between 1 and 16384"}, 200);
  // Images that cannot fit are refused before anything is rendered, with the limit.
  expect_short_error("render --backend embree --scene thesis:sphere:1 --size 16384x16384",
                     {"268435456 pixels", "limit of 33554432"}, 200, 10);
}

TEST(Limits, SceneIntegersAreReadAsWritten) {
  const test::TempDir dir;
  std::string scene = far_scene("");
  scene.replace(scene.find("\"width\": 96"), 11, "\"width\": 18446744073709551615");
  const std::string path = dir.write("wide.json", scene).string();
  expect_short_error("render --backend embree --frames 1 --scene " + path, {"render.width", "got 18446744073709551615"});
}

TEST(Limits, OutOfMemoryIsAClearErrorNotAnInternalOne) {
  // 1 GiB of address space: the 8192x4096 frame's images (1.4 GiB) cannot be allocated.
  const test::CommandResult r = test::run_shell("ulimit -v 1048576; exec " + std::string(SDFBENCH_BINARY) +
                             " render --backend embree --scene thesis:sphere:1 --size 8192x4096 --frames 1 --warmup 0",
                         60);
  const std::string line = last_line(r.output);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(line.find("sdfbench: error: out of memory"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("internal error"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace sdfbench
