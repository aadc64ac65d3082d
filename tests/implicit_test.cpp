// Implicit objects (thesis 5.1, figure 6.5): primitive distances and uv against analytic values,
// CSG trees, bounds, known-answer renders, every backend against Embree, descriptor errors.
#include <cmath>
#include <string>
#include <tuple>

#include <gtest/gtest.h>

#include "harness/image_agreement.h"
#include "renderers/frame_params.h"
#include "renderers/backend_registry.h"
#include "renderers/renderer.h"
#include "renderers/shading/cpu_shading.h"
#include "scenes/scene_loader.h"
#include "tests/test_support.h"
#include "util/error.h"

namespace sdfbench {
namespace {

using glm::vec3;
using glm::vec4;

float distance(uint32_t kind, vec4 a, vec4 b, vec3 q) { return shading::implicit_primitive_distance(kind, a, b, q); }

TEST(ImplicitPrimitive, SphereDistance) {
  const vec4 r(1.0f, 0.0f, 0.0f, 0.0f);
  EXPECT_FLOAT_EQ(distance(IMPLICIT_SPHERE, r, vec4(0.0f), {2, 0, 0}), 1.0f);
  EXPECT_FLOAT_EQ(distance(IMPLICIT_SPHERE, r, vec4(0.0f), {0, 0.5f, 0}), -0.5f);
  EXPECT_FLOAT_EQ(distance(IMPLICIT_SPHERE, r, vec4(0.0f), {0, 0, 0}), -1.0f);
}

TEST(ImplicitPrimitive, BoxDistance) {
  const vec4 h(1.0f, 2.0f, 3.0f, 0.0f);
  EXPECT_FLOAT_EQ(distance(IMPLICIT_BOX, h, vec4(0.0f), {2, 0, 0}), 1.0f);
  EXPECT_FLOAT_EQ(distance(IMPLICIT_BOX, h, vec4(0.0f), {2, 3, 0}), std::sqrt(2.0f));  // off an edge
  EXPECT_FLOAT_EQ(distance(IMPLICIT_BOX, h, vec4(0.0f), {0, 0, 0}), -1.0f);           // nearest face: x
  EXPECT_FLOAT_EQ(distance(IMPLICIT_BOX, h, vec4(0.0f), {0, 1.5f, 0}), -0.5f);
  // Rounded: flat faces stay put, a corner is a sphere of the rounding radius.
  const vec4 rounded(1.0f, 1.0f, 1.0f, 0.25f);
  EXPECT_FLOAT_EQ(distance(IMPLICIT_BOX, rounded, vec4(0.0f), {2, 0, 0}), 1.0f);
  EXPECT_NEAR(distance(IMPLICIT_BOX, rounded, vec4(0.0f), {2, 2, 2}), std::sqrt(3.0f) * 1.25f - 0.25f, 1e-6f);
}

TEST(ImplicitPrimitive, EllipsoidDistance) {
  const vec4 r(1.0f, 2.0f, 3.0f, 0.0f);
  EXPECT_FLOAT_EQ(distance(IMPLICIT_ELLIPSOID, r, vec4(0.0f), {3, 0, 0}), 2.0f);  // exact on the axes
  EXPECT_FLOAT_EQ(distance(IMPLICIT_ELLIPSOID, r, vec4(0.0f), {0, 5, 0}), 3.0f);
  EXPECT_FLOAT_EQ(distance(IMPLICIT_ELLIPSOID, r, vec4(0.0f), {0, 0, -4}), 1.0f);
  EXPECT_FLOAT_EQ(distance(IMPLICIT_ELLIPSOID, r, vec4(0.0f), {0, 0, 0}), -1.0f);  // centre: smallest radius
  EXPECT_NEAR(distance(IMPLICIT_ELLIPSOID, r, vec4(0.0f), {std::sqrt(0.5f), std::sqrt(2.0f), 0}), 0.0f, 1e-6f);
  EXPECT_LT(distance(IMPLICIT_ELLIPSOID, r, vec4(0.0f), {0.5f, 1.0f, 1.0f}), 0.0f);
  EXPECT_GT(distance(IMPLICIT_ELLIPSOID, r, vec4(0.0f), {0.9f, 1.0f, 1.0f}), 0.0f);
}

TEST(ImplicitPrimitive, CapsuleDistance) {
  const vec4 a(0.0f, 0.0f, 0.0f, 0.5f), b(0.0f, 2.0f, 0.0f, 0.0f);
  EXPECT_FLOAT_EQ(distance(IMPLICIT_CAPSULE, a, b, {1, 1, 0}), 0.5f);   // beside the segment
  EXPECT_FLOAT_EQ(distance(IMPLICIT_CAPSULE, a, b, {0, 3, 0}), 0.5f);   // beyond the top cap
  EXPECT_FLOAT_EQ(distance(IMPLICIT_CAPSULE, a, b, {0, -1, 0}), 0.5f);  // below the bottom cap
  EXPECT_FLOAT_EQ(distance(IMPLICIT_CAPSULE, a, b, {0, 1, 0}), -0.5f);
  EXPECT_FLOAT_EQ(distance(IMPLICIT_CAPSULE, a, vec4(0.0f), {0, 2, 0}), 1.5f);  // a = b: a sphere
}

TEST(ImplicitPrimitive, TorusDistance) {
  const vec4 t(2.0f, 0.5f, 0.0f, 0.0f);
  EXPECT_FLOAT_EQ(distance(IMPLICIT_TORUS, t, vec4(0.0f), {2, 0, 0}), -0.5f);  // on the core circle
  EXPECT_FLOAT_EQ(distance(IMPLICIT_TORUS, t, vec4(0.0f), {0, 0, 0}), 1.5f);   // the hole's centre
  EXPECT_FLOAT_EQ(distance(IMPLICIT_TORUS, t, vec4(0.0f), {3, 0, 0}), 0.5f);
  EXPECT_FLOAT_EQ(distance(IMPLICIT_TORUS, t, vec4(0.0f), {0, 1, -2}), 0.5f);
}

TEST(ImplicitPrimitive, PlaneDistance) {
  const vec4 p(0.0f, 1.0f, 0.0f, 1.0f);  // y = 1, inside below
  EXPECT_FLOAT_EQ(distance(IMPLICIT_PLANE, p, vec4(0.0f), {5, 3, 2}), 2.0f);
  EXPECT_FLOAT_EQ(distance(IMPLICIT_PLANE, p, vec4(0.0f), {0, 0, 0}), -1.0f);
}

TEST(ImplicitPrimitive, GeneratedUv) {
  using shading::implicit_primitive_uv;
  const vec4 unit(1.0f, 1.0f, 1.0f, 0.0f);
  // Thesis Algorithm 3.2: u = atan2(n.x, n.z) / 2pi + 0.5, v = n.y / 2 + 0.5.
  EXPECT_NEAR(implicit_primitive_uv(IMPLICIT_SPHERE, unit, vec4(0.0f), {0, 0, 1}).x, 0.5f, 1e-6f);
  EXPECT_NEAR(implicit_primitive_uv(IMPLICIT_SPHERE, unit, vec4(0.0f), {1, 0, 0}).x, 0.75f, 1e-6f);
  EXPECT_NEAR(implicit_primitive_uv(IMPLICIT_SPHERE, unit, vec4(0.0f), {0, 1, 0}).y, 1.0f, 1e-6f);
  EXPECT_NEAR(implicit_primitive_uv(IMPLICIT_ELLIPSOID, vec4(2, 1, 1, 0), vec4(0.0f), {2, 0, 0}).x, 0.75f, 1e-6f);
  // Box: the face's own coordinates, [0, 1] across it.
  const glm::vec2 face = implicit_primitive_uv(IMPLICIT_BOX, vec4(1, 2, 1, 0), vec4(0.0f), {1, 1, -0.5f});
  EXPECT_NEAR(face.x, 0.25f, 1e-6f);  // z
  EXPECT_NEAR(face.y, 0.75f, 1e-6f);  // y
  // Capsule: v runs from the bottom cap's tip (0) to the top cap's (1).
  const vec4 ca(0.0f, 0.0f, 0.0f, 0.5f), cb(0.0f, 2.0f, 0.0f, 0.0f);
  EXPECT_NEAR(implicit_primitive_uv(IMPLICIT_CAPSULE, ca, cb, {0, -0.5f, 0}).y, 0.0f, 1e-6f);
  EXPECT_NEAR(implicit_primitive_uv(IMPLICIT_CAPSULE, ca, cb, {0, 2.5f, 0}).y, 1.0f, 1e-6f);
  EXPECT_NEAR(implicit_primitive_uv(IMPLICIT_CAPSULE, ca, cb, {0.5f, 1, 0}).y, 0.5f, 1e-6f);
  // Torus: both angles; the outer equator facing +z is (0.5, 0.5).
  const glm::vec2 ring = implicit_primitive_uv(IMPLICIT_TORUS, vec4(2, 0.5f, 0, 0), vec4(0.0f), {0, 0, 2.5f});
  EXPECT_NEAR(ring.x, 0.5f, 1e-6f);
  EXPECT_NEAR(ring.y, 0.5f, 1e-6f);
  // A horizontal plane's uv is world (x, z), like the floor's.
  const glm::vec2 plane = implicit_primitive_uv(IMPLICIT_PLANE, vec4(0, 1, 0, 0), vec4(0.0f), {3, 0, -4});
  EXPECT_NEAR(plane.x, 3.0f, 1e-6f);
  EXPECT_NEAR(plane.y, -4.0f, 1e-6f);
}

ImplicitNode sphere(float radius, vec3 centre = vec3(0.0f)) {
  ImplicitNode n{.kind = ImplicitKind::Sphere, .a = vec4(radius, 0, 0, 0)};
  n.placement.translation = centre;
  return n;
}

ImplicitNode box(vec3 half_extents) { return {.kind = ImplicitKind::Box, .a = vec4(half_extents, 0.0f)}; }

ImplicitNode op(ImplicitKind kind) { return {.kind = kind}; }

// Evaluates trees with the shading program itself (implicit_trace.glsl compiled as C++).
struct NoMeshes {
  bool closest_hit(shading::Ray, float, shading::Hit&) const { return false; }
  bool any_hit(shading::Ray, float) const { return false; }
  float mesh_hit_tolerance() const { return 0.0f; }
};

class CsgTree {
 public:
  explicit CsgTree(std::vector<ImplicitNode> nodes) {
    scene_.materials.push_back(Material{});
    scene_.implicits.push_back(ImplicitObject{.nodes = std::move(nodes)});
    inputs_ = make_shading_inputs(scene_, FrameRequest{1, 1});
  }
  // Signed distance at p and the node index of the primitive deciding it.
  std::pair<float, uint32_t> at(vec3 p) const {
    const NoMeshes tracer;
    shading::CpuShading<NoMeshes> program(tracer, inputs_.frame, inputs_.materials.data(), inputs_.lights.data(),
                                          nullptr, inputs_.implicit_objects.data(), inputs_.implicit_nodes.data());
    uint32_t prim = 0;
    const float d = program.implicit_distance(0u, static_cast<uint32_t>(inputs_.implicit_nodes.size()), p, prim);
    return {d, prim};
  }

 private:
  Scene scene_;
  ShadingInputs inputs_;
};

TEST(ImplicitCsg, UnionIsTheNearerSurface) {
  const CsgTree t({sphere(1, {-1, 0, 0}), sphere(1, {1, 0, 0}), op(ImplicitKind::Union)});
  EXPECT_FLOAT_EQ(t.at({0, 0, 0}).first, 0.0f);
  EXPECT_EQ(t.at({3, 0, 0}), std::make_pair(1.0f, 1u));
  EXPECT_EQ(t.at({-3, 0, 0}), std::make_pair(1.0f, 0u));
  EXPECT_FLOAT_EQ(t.at({1, 0, 0}).first, -1.0f);
}

TEST(ImplicitCsg, IntersectionIsTheLens) {
  const CsgTree t({sphere(1, {-1, 0, 0}), sphere(1, {1, 0, 0}), op(ImplicitKind::Intersection)});
  EXPECT_FLOAT_EQ(t.at({0, 0, 0}).first, 0.0f);              // both surfaces meet at the origin
  EXPECT_EQ(t.at({1, 0, 0}), std::make_pair(1.0f, 0u));      // inside the right sphere, 1 from the left one
  EXPECT_EQ(t.at({-1.5f, 0, 0}), std::make_pair(1.5f, 1u));
  EXPECT_GT(t.at({0, 0.5f, 0}).first, 0.0f);                 // the lens is thinner than either sphere
}

TEST(ImplicitCsg, SubtractionCarvesAHole) {
  const CsgTree t({box({1, 1, 1}), sphere(0.5f), op(ImplicitKind::Subtraction)});
  EXPECT_EQ(t.at({0, 0, 0}), std::make_pair(0.5f, 1u));  // in the hole: 0.5 from its wall, the sphere's surface
  EXPECT_EQ(t.at({2, 0, 0}), std::make_pair(1.0f, 0u));  // outside the box
  EXPECT_FLOAT_EQ(t.at({0.75f, 0, 0}).first, -0.25f);    // in the material between hole and face
  EXPECT_NEAR(t.at({0.6f, 0, 0}).first, -0.1f, 1e-6f);
}

TEST(ImplicitCsg, NaryOperationsFoldLeftWithTheirChildren) {
  // box - sphere - sphere: both spheres are taken away from the box.
  const CsgTree t({box({2, 1, 1}), sphere(0.5f, {-1, 0, 0}), op(ImplicitKind::Subtraction), sphere(0.5f, {1, 0, 0}),
                   op(ImplicitKind::Subtraction)});
  EXPECT_EQ(t.at({-1, 0, 0}), std::make_pair(0.5f, 1u));
  EXPECT_EQ(t.at({1, 0, 0}), std::make_pair(0.5f, 3u));
  EXPECT_LT(t.at({0, 0, 0}).first, 0.0f);
}

TEST(ImplicitBounds, FollowTheTree) {
  Aabb b = implicit_bounds({sphere(1, {1, 2, 3})});
  EXPECT_EQ(b.min, vec3(0, 1, 2));
  EXPECT_EQ(b.max, vec3(2, 3, 4));
  b = implicit_bounds({sphere(1, {-2, 0, 0}), sphere(1, {2, 0, 0}), op(ImplicitKind::Union)});
  EXPECT_EQ(b.min, vec3(-3, -1, -1));
  EXPECT_EQ(b.max, vec3(3, 1, 1));
  b = implicit_bounds({sphere(1, {-0.5f, 0, 0}), sphere(1, {0.5f, 0, 0}), op(ImplicitKind::Intersection)});
  EXPECT_EQ(b.min, vec3(-0.5f, -1, -1));
  EXPECT_EQ(b.max, vec3(0.5f, 1, 1));
  b = implicit_bounds({box({1, 1, 1}), sphere(3), op(ImplicitKind::Subtraction)});
  EXPECT_EQ(b.max, vec3(1, 1, 1));
  // A half-space is bounded by what it cuts.
  const ImplicitNode plane{.kind = ImplicitKind::Plane, .a = vec4(0, 1, 0, 0)};
  b = implicit_bounds({sphere(1), plane, op(ImplicitKind::Intersection)});
  EXPECT_EQ(b.max, vec3(1, 1, 1));
  EXPECT_THROW(implicit_bounds({plane}), Error);
  EXPECT_THROW(implicit_bounds({sphere(1), plane, op(ImplicitKind::Union)}), Error);
  EXPECT_THROW(implicit_bounds({sphere(1, {-5, 0, 0}), sphere(1, {5, 0, 0}), op(ImplicitKind::Intersection)}), Error);
  std::vector<ImplicitNode> deep;  // right-nested: 9 operands pending at once
  for (int i = 0; i < 9; ++i) deep.push_back(sphere(1));
  for (int i = 0; i < 8; ++i) deep.push_back(op(ImplicitKind::Union));
  EXPECT_THROW(implicit_bounds(deep), Error);
}

FrameImages render(const std::string& backend, const Scene& scene, RenderMode mode, uint32_t w, uint32_t h) {
  return test::render_frame(backend, scene, mode, w, h);
}

// A camera on +z looking at the origin, nothing but implicit objects.
Scene head_on_scene(std::vector<ImplicitNode> nodes, Transform transform = {}) {
  Scene scene;
  scene.name = "implicit known answer";
  scene.materials.push_back(Material{});
  scene.implicits.push_back(ImplicitObject{.nodes = std::move(nodes), .transform = transform});
  scene.camera = {.position = {0, 0, 10}, .look_at = {0, 0, 0}, .up = {0, 1, 0}, .fov_y_degrees = 30};
  return scene;
}

// The pinhole camera ray's direction through a pixel's centre, from the kernels' frame parameters.
vec3 ray_dir(const Scene& scene, uint32_t x, uint32_t y, uint32_t w, uint32_t h) {
  const shading::FrameParams f = make_shading_inputs(scene, FrameRequest{w, h}).frame;
  const float sx = (x + 0.5f) / w * 2.0f - 1.0f, sy = 1.0f - (y + 0.5f) / h * 2.0f;
  return glm::normalize(vec3(f.camera_forward) + sx * vec3(f.camera_right) + sy * vec3(f.camera_up));
}

// One test per backend: each compiles its own kernel (all in one test: 17 s with a cold shader cache).
class ImplicitRender : public testing::TestWithParam<std::string> {};

TEST_P(ImplicitRender, SphereDepthAtImageCentre) {
  // A unit sphere scaled by 2 and centred at z = -2: its front at z = 0, 10 from the camera.
  Transform t;
  t.translation = {0, 0, -2};
  t.scale = 2.0f;
  const Scene scene = head_on_scene({sphere(1)}, t);
  const FrameImages f = render(GetParam(), scene, RenderMode::Primary, 33, 33);
  const size_t centre = 16 * 33 + 16;
  EXPECT_EQ(f.instance_id[centre], 0u);  // the first id after the (no) meshes
  EXPECT_NEAR(f.depth[centre], 10.0f, 1e-3f);
  EXPECT_GT(f.normal[centre].z, 0.999f);
  EXPECT_EQ(f.instance_id[0], shading::NO_INSTANCE_VALUE);
}

TEST_P(ImplicitRender, SubtractionHoleIsSeeThrough) {
  ImplicitNode bore{.kind = ImplicitKind::Capsule, .a = vec4(0, 0, -2, 0.4f), .b = vec4(0, 0, 2, 0)};
  const Scene scene = head_on_scene({box({1, 1, 1}), bore, op(ImplicitKind::Subtraction)});
  const FrameImages f = render(GetParam(), scene, RenderMode::Primary, 33, 33);
  EXPECT_EQ(f.instance_id[16 * 33 + 16], shading::NO_INSTANCE_VALUE);  // through the hole
  const size_t beside = 16 * 33 + 21;  // x ~ 0.73 on the front face z = 1, outside the 0.4 hole
  EXPECT_EQ(f.instance_id[beside], 0u);
  EXPECT_NEAR(f.depth[beside] * -ray_dir(scene, 21, 16, 33, 33).z, 9.0f, 1e-3f);
}

INSTANTIATE_TEST_SUITE_P(Backends, ImplicitRender, testing::ValuesIn(backend_names()),
                         [](const auto& info) { return test::backend_test_name(info.param); });

// Meshes and implicit objects together: a mirror mesh sphere, a glass implicit sphere, a
// checkered CSG object, a torus and a capsule on a checker floor.
Scene mixed_scene() {
  Scene scene;
  scene.name = "implicit agreement";
  scene.meshes.push_back(load_obj(builtin_mesh_path("sphere"), "sphere"));
  scene.materials = {
      Material{.name = "floor", .albedo = vec3(0.9f), .checker_size = 0.5f, .checker_albedo = vec3(0.2f)},
      Material{.name = "mirror", .albedo = vec3(0.8f), .reflectance = 0.8f},
      Material{.name = "glass", .albedo = vec3(0.9f), .transmission = 0.9f, .ior = 1.5f},
      Material{.name = "check", .albedo = {0.9f, 0.5f, 0.2f}, .checker_size = 0.125f, .checker_albedo = {0.2f, 0.3f, 0.8f}},
      Material{.name = "red", .albedo = {0.8f, 0.2f, 0.2f}}};
  Instance ball{.mesh = 0, .material = 1};
  ball.transform.translation = {-1.8f, 0.8f, -0.5f};
  ball.transform.scale = 0.8f;
  scene.instances.push_back(ball);
  auto add = [&](std::vector<ImplicitNode> nodes, uint32_t material, vec3 at, float degrees = 0.0f) {
    ImplicitObject o{.nodes = std::move(nodes), .material = material};
    o.transform.translation = at;
    o.transform.rotation = glm::angleAxis(glm::radians(degrees), vec3(0, 1, 0));
    scene.implicits.push_back(o);
  };
  add({sphere(0.5f)}, 2, {0.9f, 0.5f, 1.3f});
  ImplicitNode bore{.kind = ImplicitKind::Capsule, .a = vec4(-2, 0, 0, 0.35f), .b = vec4(2, 0, 0, 0)};
  add({box({0.6f, 0.6f, 0.6f}), sphere(0.8f), op(ImplicitKind::Intersection), bore, op(ImplicitKind::Subtraction)}, 3,
      {1.6f, 0.6f, -0.6f}, -70.0f);
  add({ImplicitNode{.kind = ImplicitKind::Torus, .a = vec4(0.5f, 0.15f, 0, 0)}}, 3, {-0.2f, 0.15f, 0.3f});
  add({ImplicitNode{.kind = ImplicitKind::Ellipsoid, .a = vec4(0.3f, 0.6f, 0.3f, 0)},
       ImplicitNode{.kind = ImplicitKind::Capsule, .a = vec4(0, 0, -0.5f, 0.15f), .b = vec4(0, 0, 0.5f, 0)},
       op(ImplicitKind::Union)},
      4, {-0.3f, 0.6f, -2.2f}, -20.0f);
  scene.floor = Floor{.enabled = true, .height = 0.0f, .material = 0};
  scene.lights.push_back(Light{.direction = glm::normalize(vec3(0.5f, 1.0f, 0.3f))});
  scene.lights.push_back(Light{.kind = Light::Kind::Point, .position = {-3.0f, 4.0f, 4.0f}, .color = vec3(0.3f)});
  scene.camera = Camera{.position = {0.0f, 2.5f, 6.0f}, .look_at = {0.0f, 0.6f, 0.0f}};
  return scene;
}

// One test per mode and backend: each compiles its own kernel, and a whitted kernel with implicit
// objects takes lavapipe 5-7 s to compile with a cold shader cache.
class ImplicitAgreement : public testing::TestWithParam<std::tuple<RenderMode, std::string>> {};

TEST_P(ImplicitAgreement, DrawsWhatEmbreeDraws) {
  const auto& [mode, backend] = GetParam();
  const Scene scene = mixed_scene();
  const FrameImages reference = render("embree", scene, mode, 96, 54);
  // The picture holds the mesh (id 0) and every implicit object (ids 1-4).
  std::vector<size_t> seen(5, 0);
  for (uint32_t id : reference.instance_id)
    if (id < seen.size()) ++seen[id];
  for (size_t id = 0; id < seen.size(); ++id) EXPECT_GT(seen[id], 10u) << "instance " << id;
  const Agreement g = compare_frames(render(backend, scene, mode, 96, 54), reference);
  EXPECT_GE(g.hit_percent, 99.5);
  EXPECT_GE(g.id_percent, 99.0);
  EXPECT_GE(g.psnr, 30.0);
  EXPECT_EQ(check_thresholds(g, AgreementThresholds{}), "");
}

INSTANTIATE_TEST_SUITE_P(Modes, ImplicitAgreement,
                         testing::Combine(testing::Values(RenderMode::Primary, RenderMode::Whitted),
                                          testing::ValuesIn(test::backends_but_the_reference())),
                         [](const auto& info) {
                           return to_string(std::get<0>(info.param)) + "_" + test::backend_test_name(std::get<1>(info.param));
                         });

// Descriptor: an implicit-only scene parses; every bad shape names its field.
const char* kImplicitScene = R"({
  "materials": {"clay": {"albedo": [0.8, 0.6, 0.5]}},
  "implicits": [{"material": "clay", "translate": [0, 1, 0], "scale": 2,
                 "shape": {"type": "subtraction", "children": [
                   {"type": "box", "half_extents": [1, 1, 1], "rounding": 0.1},
                   {"type": "sphere", "radius": 1.2, "translate": [0, 0.5, 0]},
                   {"type": "capsule", "a": [0, 0, -2], "b": [0, 0, 2], "radius": 0.3}]}}],
  "camera": {"position": [0, 2, 8], "look_at": [0, 1, 0]}
})";

std::string error_of(const std::string& json) {
  try {
    parse_scene_json(json, "implicit.json");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ImplicitDescriptor, ParsesAnImplicitOnlyScene) {
  const Scene scene = parse_scene_json(kImplicitScene, "implicit.json");
  EXPECT_TRUE(scene.meshes.empty());
  EXPECT_TRUE(scene.instances.empty());
  ASSERT_EQ(scene.implicits.size(), 1u);
  const ImplicitObject& o = scene.implicits[0];
  EXPECT_FLOAT_EQ(o.transform.scale, 2.0f);
  ASSERT_EQ(o.nodes.size(), 5u);  // box sphere - capsule -
  EXPECT_EQ(o.nodes[0].kind, ImplicitKind::Box);
  EXPECT_FLOAT_EQ(o.nodes[0].a.w, 0.1f);
  EXPECT_EQ(o.nodes[1].placement.translation, vec3(0, 0.5f, 0));
  EXPECT_EQ(o.nodes[2].kind, ImplicitKind::Subtraction);
  EXPECT_EQ(o.nodes[3].kind, ImplicitKind::Capsule);
  EXPECT_EQ(o.nodes[3].b, vec4(0, 0, 2, 0));
  EXPECT_FLOAT_EQ(o.nodes[3].a.w, 0.3f);
  EXPECT_EQ(o.nodes[4].kind, ImplicitKind::Subtraction);
  const Aabb bounds = scene.bounds();  // world: object box x 2, raised by 1
  EXPECT_FLOAT_EQ(bounds.max.y, 3.0f);
}

std::string variant(const std::string& from, const std::string& to) {
  std::string s = kImplicitScene;
  const size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return s.replace(at, from.size(), to);
}

struct BadShape {
  const char* from;
  const char* to;
  const char* field;
  const char* problem;
};

class ImplicitDescriptorRejects : public testing::TestWithParam<BadShape> {};

TEST_P(ImplicitDescriptorRejects, NamingFieldAndProblem) {
  const BadShape& bad = GetParam();
  const std::string e = error_of(variant(bad.from, bad.to));
  ASSERT_FALSE(e.empty()) << "accepted: " << bad.to;
  EXPECT_NE(e.find("implicit.json"), std::string::npos) << e;
  EXPECT_NE(e.find(bad.field), std::string::npos) << e;
  EXPECT_NE(e.find(bad.problem), std::string::npos) << e;
}

const char* kSphere = R"({"type": "sphere", "radius": 1.2, "translate": [0, 0.5, 0]})";

INSTANTIATE_TEST_SUITE_P(
    Shapes, ImplicitDescriptorRejects,
    testing::Values(
        BadShape{"\"type\": \"sphere\"", "\"type\": \"cone\"", "implicits[0].shape.children[1].type", "unknown shape type 'cone'"},
        BadShape{"\"radius\": 1.2", "\"radius\": -1", "implicits[0].shape.children[1].radius", "must be > 0"},
        BadShape{"\"radius\": 1.2", "\"radis\": 1.2", "implicits[0].shape.children[1].radis", "unknown field"},
        BadShape{"\"radius\": 0.3", "\"r\": 0.3", "implicits[0].shape.children[2].r", "unknown field"},
        BadShape{", \"radius\": 0.3", "", "implicits[0].shape.children[2].radius", "missing required field"},
        BadShape{"[1, 1, 1], \"rounding\": 0.1", "[1, 1, 1], \"rounding\": 2", "children[0].rounding", "must be in"},
        BadShape{"[1, 1, 1]", "[1, 0, 1]", "children[0].half_extents", "must be > 0"},
        BadShape{"\"material\": \"clay\"", "\"material\": \"gold\"", "implicits[0].material", "unknown material 'gold'"},
        BadShape{"\"scale\": 2", "\"scale\": 0", "implicits[0].scale", "must be in"},
        BadShape{"\"type\": \"subtraction\"", "\"type\": \"union\", \"smooth\": 1", "implicits[0].shape.smooth", "unknown field"},
        BadShape{kSphere, R"({"type": "plane", "normal": [0, 0, 0]})", "children[1].normal", "must not be zero"},
        BadShape{"\"scale\": 2,", "\"scale\": 2, \"unused\": 1,", "implicits[0].unused", "unknown field"}),
    [](const testing::TestParamInfo<BadShape>& info) { return "case" + std::to_string(info.index); });

TEST(ImplicitDescriptor, RejectsEmptyIntersectionsOversizedTreesAndEmptyScenes) {
  const std::string disjoint = R"({"implicits": [{"shape": {"type": "intersection", "children": [
      {"type": "sphere", "radius": 1}, {"type": "sphere", "radius": 1, "translate": [5, 0, 0]}]}}],
      "camera": {"position": [0, 2, 8], "look_at": [0, 1, 0]}})";
  std::string e = error_of(disjoint);
  EXPECT_NE(e.find("implicits[0].shape: the shape is empty"), std::string::npos) << e;

  e = error_of(R"({"implicits": [{"shape": {"type": "union", "children": [
      {"type": "sphere", "radius": 1}, {"type": "plane", "normal": [0, 1, 0]}]}}],
      "camera": {"position": [0, 2, 8], "look_at": [0, 1, 0]}})");
  EXPECT_NE(e.find("implicits[0].shape: the shape is unbounded"), std::string::npos) << e;

  std::string children;
  for (int i = 0; i < 40; ++i) children += std::string(i ? ", " : "") + R"({"type": "sphere", "radius": 1})";
  e = error_of(R"({"implicits": [{"shape": {"type": "union", "children": [)" + children +
               R"(]}}], "camera": {"position": [0, 2, 8], "look_at": [0, 1, 0]}})");
  EXPECT_NE(e.find("too many nodes"), std::string::npos) << e;

  std::string nested = R"({"type": "sphere", "radius": 1})";
  for (int i = 0; i < 9; ++i) nested = R"({"type": "union", "children": [{"type": "sphere", "radius": 1}, )" + nested + "]}";
  e = error_of(R"({"implicits": [{"shape": )" + nested + R"(}], "camera": {"position": [0, 2, 8], "look_at": [0, 1, 0]}})");
  EXPECT_NE(e.find("implicits[0].shape: the shape needs an evaluation stack deeper than 8"), std::string::npos) << e;

  e = error_of(R"({"implicits": [{"shape": {"type": "union", "children": [{"type": "sphere", "radius": 1}]}}],
      "camera": {"position": [0, 2, 8], "look_at": [0, 1, 0]}})");
  EXPECT_NE(e.find("implicits[0].shape.children: an operation needs at least 2 children"), std::string::npos) << e;

  e = error_of(R"({"implicits": [], "camera": {"position": [0, 2, 8], "look_at": [0, 1, 0]}})");
  EXPECT_NE(e.find("implicits: a scene needs at least one instance or implicit object"), std::string::npos) << e;
  e = error_of(R"({"camera": {"position": [0, 2, 8], "look_at": [0, 1, 0]}})");
  EXPECT_NE(e.find("at least one instance or implicit object"), std::string::npos) << e;
}

}  // namespace
}  // namespace sdfbench
