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

#include "renderers/frame_params.h"
#include "scenes/scene_loader.h"
#include "tests/test_support.h"

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
  const std::string scene = dir.write("e29.json", far_scene("1e29")).string();
  expect_short_error("build --scene " + scene, {"--hash-cell 10 gives 1e+28 x 1 x 1 = 1e+28 cells", "limit of 67108864"});
  expect_short_error("build --scene " + scene + " --hash-cell 1e-30", {"--hash-cell 1e-30 gives 1e+59 x", "e+119 cells"});
}

TEST(Limits, NumericFlagsHaveSaneRangesAndShortMessages) {
  const std::string render = "render --backend sdf-cpu --scene thesis:sphere:1 --size 16x9 --frames 1 --warmup 0";
  expect_short_error(render + " --hash-cell 0", {"--hash-cell", "[1e-30, 1e+30]"}, 200);
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
