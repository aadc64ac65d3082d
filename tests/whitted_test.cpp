// Whitted mode (thesis 5.3): every backend draws what Embree draws, known answers for mirrors,
// glass and image textures, and --max-depth changes exactly the mirrors.
#include <cmath>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "harness/image_agreement.h"
#include "renderers/frame_params.h"
#include "renderers/backend_registry.h"
#include "renderers/renderer.h"
#include "scenes/scene_loader.h"
#include "tests/test_support.h"

namespace sdfbench {
namespace {

constexpr uint32_t kWidth = 96, kHeight = 54;

FrameImages render(const std::string& backend, const Scene& scene, std::optional<uint32_t> max_depth = {}) {
  auto renderer = create_renderer(backend, BackendOptions{});
  renderer->prepare(scene);
  return renderer->render(FrameRequest{kWidth, kHeight, RenderMode::Whitted, true, max_depth}).images;
}

// A checkerboard floor and the sphere mesh (radius 1) placed by add_sphere.
Scene base_scene() {
  Scene scene;
  scene.name = "whitted test";
  scene.meshes.push_back(load_obj(builtin_mesh_path("sphere"), "sphere"));
  scene.materials.push_back(
      Material{.name = "floor", .albedo = glm::vec3(0.9f), .checker_size = 0.5f, .checker_albedo = glm::vec3(0.2f)});
  scene.floor = Floor{.enabled = true, .height = 0.0f, .material = 0};
  scene.camera = Camera{.position = {0.0f, 2.5f, 6.0f}, .look_at = {0.0f, 0.8f, 0.0f}};
  return scene;
}

uint32_t add_material(Scene& scene, Material m) {
  scene.materials.push_back(m);
  return static_cast<uint32_t>(scene.materials.size() - 1);
}

void add_sphere(Scene& scene, glm::vec3 centre, float radius, uint32_t material) {
  Instance ball{.mesh = 0, .material = material};
  ball.transform.translation = centre;
  ball.transform.scale = radius;
  scene.instances.push_back(ball);
}

// A mirror, a glass ball and a diffuse ball, lit by a directional and a point light.
Scene mirror_and_glass_scene() {
  Scene scene = base_scene();
  add_sphere(scene, {-1.2f, 1.0f, 0.0f}, 1.0f, add_material(scene, {.name = "mirror", .reflectance = 0.9f}));
  add_sphere(scene, {1.2f, 1.0f, 0.6f}, 0.9f, add_material(scene, {.name = "glass", .transmission = 0.9f, .ior = 1.5f}));
  add_sphere(scene, {0.3f, 0.6f, -2.0f}, 0.6f, add_material(scene, {.name = "red", .albedo = {0.8f, 0.2f, 0.2f}}));
  scene.lights.push_back(Light{.direction = glm::normalize(glm::vec3(0.5f, 1.0f, 0.3f))});
  scene.lights.push_back(Light{.kind = Light::Kind::Point, .position = {-3.0f, 4.0f, 4.0f}, .color = glm::vec3(0.3f)});
  return scene;
}

glm::vec3 display_encode(glm::vec3 c) { return glm::pow(glm::clamp(c, 0.0f, 1.0f), glm::vec3(1.0f / 2.2f)); }

glm::vec3 sky(const Scene& scene, float dir_y) {
  return glm::mix(scene.sky.horizon, scene.sky.zenith, std::sqrt(glm::clamp(dir_y, 0.0f, 1.0f)));
}

// The pinhole camera ray through a pixel's centre, in closed form from the scene's camera (not
// from the frame parameters the kernels get, which are under test): a vertical field of view
// fov_y, square pixels (the horizontal extent is the aspect ratio times the vertical), +y up.
shading::Ray pixel_ray(const Scene& scene, uint32_t x, uint32_t y) {
  const Camera& c = scene.camera;
  const glm::vec3 forward = glm::normalize(c.look_at - c.position);
  const glm::vec3 right = glm::normalize(glm::cross(forward, c.up)), up = glm::cross(right, forward);
  const float half_height = std::tan(glm::radians(c.fov_y_degrees) / 2.0f), half_width = half_height * kWidth / kHeight;
  const float sx = (x + 0.5f) / kWidth * 2.0f - 1.0f, sy = 1.0f - (y + 0.5f) / kHeight * 2.0f;
  return {c.position, glm::normalize(forward + sx * half_width * right + sy * half_height * up)};
}

TEST(Whitted, EveryBackendAgreesWithEmbree) {
  const Scene scene = mirror_and_glass_scene();
  const FrameImages reference = render("embree", scene);
  for (const std::string& backend : backend_names()) {
    if (backend == "embree") continue;
    const Agreement g = compare_frames(render(backend, scene), reference);
    EXPECT_EQ(check_thresholds(g, AgreementThresholds{}), "") << backend << ": PSNR " << g.psnr;
  }
}

// Whitted in passes (one ray per pixel per dispatch, for drivers with a loop cap) and in one
// invocation per pixel trace the same rays in the same order: the images are identical.
TEST(Whitted, PassesAndOneInvocationGiveTheSameImage) {
  const Scene scene = mirror_and_glass_scene();
  for (const char* backend : {"tri-aabb", "sdf-octree"}) {
    FrameResult frames[2];
    for (bool passes : {false, true}) {
      BackendOptions options;
      options.whitted_passes = passes;
      auto renderer = create_renderer(backend, options);
      renderer->prepare(scene);
      frames[passes] = renderer->render(FrameRequest{kWidth, kHeight, RenderMode::Whitted, true, {}, true});
    }
    EXPECT_EQ(frames[0].images.color, frames[1].images.color) << backend;
    EXPECT_EQ(frames[0].images.instance_id, frames[1].images.instance_id) << backend;
    EXPECT_EQ(frames[0].rays, frames[1].rays) << backend;
    EXPECT_GT(frames[0].rays, uint64_t{kWidth} * kHeight) << backend;  // secondary rays were traced
    EXPECT_EQ(frames[0].counters, frames[1].counters) << backend;
  }
  const std::string command = "render --scene thesis:sphere:5 --backend tri-aabb --size 16x9 --frames 1 --mode whitted";
  EXPECT_EQ(test::run_sdfbench(command + " --whitted-passes on").exit_code, 0);
  const test::CommandResult bad = test::run_sdfbench(command + " --whitted-passes sometimes");
  EXPECT_EQ(bad.exit_code, 1) << bad.output;
  EXPECT_NE(bad.output.find("--whitted-passes"), std::string::npos) << bad.output;
}

TEST(Whitted, CommandLineTakesModeAndMaxDepth) {
  const test::CommandResult r = test::run_sdfbench(
      "compare --scene thesis:sphere:5 --backends embree,tri-aabb --size 32x18 --mode whitted --max-depth 2");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("whitted (max depth 2)"), std::string::npos) << r.output;
  EXPECT_NE(test::run_sdfbench("render --scene thesis:sphere:5 --backend embree --max-depth 17").exit_code, 0);
}

// A perfect mirror floor with nothing in view: every pixel is the sky, straight or mirrored.
TEST(WhittedKnownAnswer, MirrorFloorReflectsTheSky) {
  Scene scene = base_scene();
  scene.materials[0] = Material{.name = "mirror floor", .reflectance = 1.0f};
  add_sphere(scene, {0.0f, 1.0f, 20.0f}, 0.5f, 0);  // behind the camera: bounds only
  scene.camera = Camera{.position = {0.0f, 1.0f, 0.0f}, .look_at = {0.0f, 0.5f, -5.0f}};
  const float tmax = make_shading_inputs(scene, FrameRequest{kWidth, kHeight}).frame.tracing.z;
  for (const char* backend : {"embree", "tri-aabb"}) {
    const FrameImages f = render(backend, scene);
    size_t mirrored = 0;
    for (uint32_t y = 0; y < kHeight; ++y) {
      for (uint32_t x = 0; x < kWidth; ++x) {
        const shading::Ray ray = pixel_ray(scene, x, y);
        const bool floor = ray.dir.y < 0.0f && -ray.origin.y / ray.dir.y < tmax;
        mirrored += floor;
        const glm::vec3 expected = display_encode(sky(scene, floor ? -ray.dir.y : ray.dir.y));
        const glm::vec3 got(f.color[y * kWidth + x]);
        ASSERT_LT(glm::length(got - expected), 1e-4f) << backend << " pixel " << x << "," << y;
      }
    }
    EXPECT_GT(mirrored, kWidth * kHeight / 4) << backend;
  }
}

// Refraction with an index of 1 bends nothing and Fresnel reflects nothing: looking down at a
// checkerboard through a glass ball shows the checkerboard as if the ball were not there.
TEST(WhittedKnownAnswer, GlassOfIndexOneIsInvisible) {
  Scene scene = base_scene();
  scene.ambient = 1.0f;  // no lights: every floor point is its albedo
  add_sphere(scene, {0.0f, 1.5f, 0.0f}, 1.0f, add_material(scene, {.name = "air", .transmission = 1.0f, .ior = 1.0f}));
  scene.camera = Camera{.position = {0.0f, 6.0f, 4.0f}, .look_at = {0.0f, 0.0f, 0.0f}, .fov_y_degrees = 30.0f};
  for (const char* backend : {"embree", "tri-aabb"}) {
    const FrameImages f = render(backend, scene, 4);
    size_t through_glass = 0, wrong = 0;
    for (uint32_t y = 0; y < kHeight; ++y) {
      for (uint32_t x = 0; x < kWidth; ++x) {
        const shading::Ray ray = pixel_ray(scene, x, y);
        const glm::vec3 p = ray.origin - ray.origin.y / ray.dir.y * ray.dir;
        const bool odd = static_cast<int>(std::floor(p.x / 0.5f) + std::floor(p.z / 0.5f)) % 2 != 0;
        const glm::vec3 expected = display_encode(glm::vec3(odd ? 0.2f : 0.9f));
        through_glass += f.instance_id[y * kWidth + x] == 0;
        wrong += glm::length(glm::vec3(f.color[y * kWidth + x]) - expected) > 1e-3f;
      }
    }
    EXPECT_GT(through_glass, kWidth * kHeight / 10) << backend;
    EXPECT_LE(wrong, kWidth * kHeight / 200) << backend << ": " << wrong;  // checker edges moved by ray offsets
  }
}

// max_depth 0 keeps only each hit's local term: only pixels that see a mirror change at 1.
TEST(Whitted, MaxDepthZeroAndOneDifferExactlyOnMirrors) {
  const Scene scene = mirror_and_glass_scene();
  for (const char* backend : {"embree", "tri-aabb"}) {
    const FrameImages d0 = render(backend, scene, 0), d1 = render(backend, scene, 1);
    size_t mirror = 0, wrong = 0;
    for (size_t i = 0; i < d0.color.size(); ++i) {
      const bool sees_mirror = d0.instance_id[i] == 0 || d0.instance_id[i] == 1;  // the mirror and the glass
      mirror += sees_mirror;
      wrong += sees_mirror == (d0.color[i] == d1.color[i]);
    }
    EXPECT_GT(mirror, 200u) << backend;
    EXPECT_EQ(wrong, 0u) << backend;
  }
}

// An image texture on the floor: 4x2 texels, one repeat per 2 units, uv (0, 0) the image's
// bottom-left corner, bilinear with wrap-around; loaded from a descriptor-relative EXR.
TEST(WhittedKnownAnswer, FloorImageTextureIsBilinear) {
  test::TempDir dir;
  const int w = 4, h = 2;
  float texels[h][w][3];  // red grows to the right, green downwards
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      texels[y][x][0] = 0.1f + 0.2f * x;
      texels[y][x][1] = 0.2f + 0.6f * y;
      texels[y][x][2] = 0.5f;
    }
  }
  auto out = OIIO::ImageOutput::create("exr");
  ASSERT_TRUE(out->open((dir.path() / "tex.exr").string(), OIIO::ImageSpec(w, h, 3, OIIO::TypeDesc::FLOAT)));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, texels));
  out->close();
  const auto descriptor = dir.write("scene.json", R"({
    "meshes": {"ball": {"builtin": "sphere"}},
    "materials": {"tiles": {"albedo": [1, 1, 1], "texture": {"file": "tex.exr", "size": 2}}},
    "instances": [{"mesh": "ball", "translate": [0, 1, -30], "scale": 0.1}],
    "camera": {"position": [0.3, 3, 2], "look_at": [0, 0, 0]},
    "floor": {}, "ambient": 1.0})");
  const Scene scene = load_scene_file(descriptor);
  auto texel = [&](int x, int y) {  // wrapping around
    const float* t = texels[(y % h + h) % h][(x % w + w) % w];
    return glm::vec3(t[0], t[1], t[2]);
  };
  for (const char* backend : {"embree", "tri-aabb"}) {
    const FrameImages f = render(backend, scene);
    for (uint32_t y = 0; y < kHeight; ++y) {
      for (uint32_t x = 0; x < kWidth; ++x) {
        const shading::Ray ray = pixel_ray(scene, x, y);
        const glm::vec3 p = ray.origin - ray.origin.y / ray.dir.y * ray.dir;
        const float s = p.x / 2.0f * w - 0.5f, t = (1.0f - p.z / 2.0f) * h - 0.5f;  // image x, y (rows from the top)
        const int x0 = static_cast<int>(std::floor(s)), y0 = static_cast<int>(std::floor(t));
        const float fx = s - x0, fy = t - y0;
        const glm::vec3 c = glm::mix(glm::mix(texel(x0, y0), texel(x0 + 1, y0), fx),
                                     glm::mix(texel(x0, y0 + 1), texel(x0 + 1, y0 + 1), fx), fy);
        ASSERT_LT(glm::length(glm::vec3(f.color[y * kWidth + x]) - display_encode(c)), 2e-3f)
            << backend << " pixel " << x << "," << y;
      }
    }
  }
}

}  // namespace
}  // namespace sdfbench
