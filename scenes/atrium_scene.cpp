#include "scenes/atrium_scene.h"

#include <cmath>
#include <vector>

#include <glm/gtc/constants.hpp>

#include "scenes/thesis_layout.h"
#include "util/error.h"

namespace sdfbench {
namespace {

// Meshes are built from quads and triangles given with the direction they face: the corners are
// ordered so that each face is counter-clockwise seen from outside (the SDF backends' sign).
struct MeshBuilder {
  Mesh mesh;
  void triangle(glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 outward) {
    if (glm::dot(glm::cross(b - a, c - a), outward) < 0.0f) std::swap(b, c);
    const auto base = static_cast<uint32_t>(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), {a, b, c});
    mesh.triangles.emplace_back(base, base + 1, base + 2);
  }
  void quad(glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, glm::vec3 outward) {  // a b c d around the quad
    triangle(a, b, c, outward);
    triangle(a, c, d, outward);
  }
  void box(glm::vec3 lo, glm::vec3 hi) {
    const glm::vec3 c[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z},
                            {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
    quad(c[0], c[1], c[2], c[3], {0, 0, -1});
    quad(c[4], c[5], c[6], c[7], {0, 0, 1});
    quad(c[0], c[1], c[5], c[4], {0, -1, 0});
    quad(c[3], c[2], c[6], c[7], {0, 1, 0});
    quad(c[0], c[3], c[7], c[4], {-1, 0, 0});
    quad(c[1], c[2], c[6], c[5], {1, 0, 0});
  }
  Mesh finish(std::string name) {
    mesh.name = std::move(name);
    finish_mesh(mesh);
    return std::move(mesh);
  }
};

// A fluted column of height h and radius r standing on y = 0 (base and capital blocks), with
// `sides` around and `rings` up; closed.
Mesh column(float r, float h, uint32_t sides, uint32_t rings) {
  MeshBuilder b;
  b.box({-1.3f * r, 0.0f, -1.3f * r}, {1.3f * r, 0.1f * h, 1.3f * r});  // base
  b.box({-1.3f * r, 0.9f * h, -1.3f * r}, {1.3f * r, h, 1.3f * r});     // capital
  const float y0 = 0.1f * h, y1 = 0.9f * h;
  auto at = [&](uint32_t i, uint32_t j) {
    const float a = glm::two_pi<float>() * float(i % sides) / float(sides);
    const float flute = 1.0f - 0.06f * float(i % 2);  // alternate sides recessed: flutes
    const float y = y0 + (y1 - y0) * float(j) / float(rings);
    return glm::vec3(r * flute * std::cos(a), y, r * flute * std::sin(a));
  };
  for (uint32_t j = 0; j < rings; ++j)
    for (uint32_t i = 0; i < sides; ++i) {
      const glm::vec3 a = at(i, j), c = at(i + 1, j + 1), mid = 0.5f * (a + c);
      b.quad(a, at(i + 1, j), c, at(i, j + 1), glm::vec3(mid.x, 0.0f, mid.z));
    }
  for (uint32_t i = 0; i < sides; ++i) {  // caps (inside the blocks, keeping the shaft closed)
    b.triangle({0.0f, y0, 0.0f}, at(i, 0), at(i + 1, 0), {0, -1, 0});
    b.triangle({0.0f, y1, 0.0f}, at(i, rings), at(i + 1, rings), {0, 1, 0});
  }
  return b.finish("column");
}

// A semicircular arch in the xy plane springing at x = -span/2 and span/2 (y = 0), its ring
// `width` wide radially and `depth` deep in z, with `segments` along the half circle; closed.
Mesh arch(float span, float width, float depth, uint32_t segments) {
  MeshBuilder b;
  const float r0 = 0.5f * span, r1 = r0 + width, z = 0.5f * depth;
  auto ring = [&](float r, uint32_t i, float zz) {
    const float a = glm::pi<float>() * float(i) / float(segments);
    return glm::vec3(r * std::cos(a), r * std::sin(a), zz);
  };
  for (uint32_t i = 0; i < segments; ++i) {
    const float a = glm::pi<float>() * (float(i) + 0.5f) / float(segments);
    const glm::vec3 radial(std::cos(a), std::sin(a), 0.0f);
    b.quad(ring(r0, i, -z), ring(r0, i + 1, -z), ring(r0, i + 1, z), ring(r0, i, z), -radial);  // intrados
    b.quad(ring(r1, i, -z), ring(r1, i + 1, -z), ring(r1, i + 1, z), ring(r1, i, z), radial);   // extrados
    b.quad(ring(r0, i, z), ring(r0, i + 1, z), ring(r1, i + 1, z), ring(r1, i, z), {0, 0, 1});
    b.quad(ring(r0, i, -z), ring(r0, i + 1, -z), ring(r1, i + 1, -z), ring(r1, i, -z), {0, 0, -1});
  }
  for (uint32_t i : {0u, segments})  // the springings
    b.quad(ring(r0, i, -z), ring(r1, i, -z), ring(r1, i, z), ring(r0, i, z), {0, -1, 0});
  return b.finish("arch");
}

}  // namespace

AtriumSpec parse_atrium_spec(const std::string& spec) {
  std::vector<std::string> parts;
  for (size_t start = 0;;) {
    const size_t colon = spec.find(':', start);
    parts.push_back(spec.substr(start, colon == std::string::npos ? std::string::npos : colon - start));
    if (colon == std::string::npos) break;
    start = colon + 1;
  }
  if (parts.empty() || parts.size() > 3 || parts[0] != "atrium")
    throw Error("scene '" + spec + "': expected atrium[:<detail>[:<camera>]], e.g. atrium:4:0");
  AtriumSpec result;
  if (parts.size() > 1) {
    const uint64_t detail = parse_spec_integer(parts[1], spec, "detail");
    if (detail < 1 || detail > kAtriumMaxDetail)
      throw Error("scene '" + spec + "': detail must be 1 to " + std::to_string(kAtriumMaxDetail));
    result.detail = static_cast<uint32_t>(detail);
  }
  if (parts.size() > 2) {
    const uint64_t camera = parse_spec_integer(parts[2], spec, "camera");
    if (camera >= kAtriumCameras)
      throw Error("scene '" + spec + "': camera must be 0 to " + std::to_string(kAtriumCameras - 1));
    result.camera = static_cast<uint32_t>(camera);
  }
  return result;
}

Scene make_atrium_scene(const AtriumSpec& spec) {
  Scene scene;
  scene.name = "atrium:" + std::to_string(spec.detail) + ":" + std::to_string(spec.camera);
  // Materials: stone, marble checker, bronze, mirror, glass, dark stone.
  scene.materials = {
      Material{.name = "stone", .albedo = {0.76f, 0.72f, 0.64f}},
      Material{.name = "marble", .albedo = {0.88f, 0.86f, 0.82f}, .checker_size = 2.0f, .checker_albedo = {0.22f, 0.2f, 0.2f}},
      Material{.name = "bronze", .albedo = {0.62f, 0.48f, 0.3f}, .reflectance = 0.25f},
      Material{.name = "mirror", .albedo = {0.9f, 0.9f, 0.9f}, .reflectance = 0.9f},
      Material{.name = "glass", .albedo = {0.9f, 0.95f, 0.95f}, .reflectance = 0.05f, .transmission = 0.85f, .ior = 1.5f},
      Material{.name = "dark stone", .albedo = {0.35f, 0.33f, 0.32f}},
  };
  enum { kStone, kMarble, kBronze, kMirror, kGlass, kDark };
  auto instance = [&](uint32_t mesh, uint32_t material, glm::vec3 at, float yaw = 0.0f) {
    Instance i{.mesh = mesh, .material = material};
    i.transform.translation = at;
    i.transform.rotation = glm::angleAxis(glm::radians(yaw), glm::vec3(0, 1, 0));
    scene.instances.push_back(i);
  };
  // A new mesh and its first instance.
  auto add = [&](Mesh mesh, uint32_t material, glm::vec3 at = glm::vec3(0.0f)) {
    scene.meshes.push_back(std::move(mesh));
    const auto id = static_cast<uint32_t>(scene.meshes.size() - 1);
    instance(id, material, at);
    return id;
  };
  // The hall: 40 x 14 x 24 (x from -20 to 20, z from -12 to 12), walls 0.6 thick.
  const float hx = 20.0f, hz = 12.0f, height = 14.0f, t = 0.6f;
  scene.floor = {.enabled = true, .height = 0.0f, .material = kMarble};  // the checker is in world x, z
  // Long walls (z = +-12) with 6 tall windows each, glazed; end walls with a door (z) and a
  // mirror panel on the far one.
  MeshBuilder walls, panes;
  const int windows = 6;
  const float bay = 2.0f * hx / windows, win_w = 2.2f, win_lo = 4.0f, win_hi = 10.0f;
  for (float side : {-1.0f, 1.0f}) {
    const float z0 = side * hz, z1 = side * (hz + t);
    const float zl = std::min(z0, z1), zh = std::max(z0, z1);
    for (int w = 0; w < windows; ++w) {
      const float cx = -hx + bay * (float(w) + 0.5f);
      const float pier_lo = cx - 0.5f * bay, pier_hi = cx - 0.5f * win_w;
      walls.box({pier_lo, 0.0f, zl}, {pier_hi, height, zh});                              // pier left of the window
      walls.box({cx + 0.5f * win_w, 0.0f, zl}, {cx + 0.5f * bay, height, zh});             // pier right of it
      walls.box({pier_hi, 0.0f, zl}, {cx + 0.5f * win_w, win_lo, zh});                    // below
      walls.box({pier_hi, win_hi, zl}, {cx + 0.5f * win_w, height, zh});                   // above
      panes.box({pier_hi, win_lo, 0.5f * (zl + zh) - 0.02f}, {cx + 0.5f * win_w, win_hi, 0.5f * (zl + zh) + 0.02f});
    }
  }
  for (float side : {-1.0f, 1.0f}) {
    const float x0 = side * hx, x1 = side * (hx + t);
    const float xl = std::min(x0, x1), xh = std::max(x0, x1);
    walls.box({xl, 0.0f, -hz - t}, {xh, height, -2.0f});  // a door 4 wide, 6 high
    walls.box({xl, 0.0f, 2.0f}, {xh, height, hz + t});
    walls.box({xl, 6.0f, -2.0f}, {xh, height, 2.0f});
  }
  add(walls.finish("walls"), kStone);
  add(panes.finish("window panes"), kGlass);
  {
    MeshBuilder mirror;
    mirror.box({hx - 0.05f, 7.0f, -8.0f}, {hx, 12.0f, -3.0f});  // on the far wall, beside the door
    mirror.box({hx - 0.05f, 7.0f, 3.0f}, {hx, 12.0f, 8.0f});
    add(mirror.finish("mirrors"), kMirror);
  }
  // Two colonnades (z = +-6) of 10 columns with arches between, a gallery slab above each aisle.
  const uint32_t sides = 24 * spec.detail, rings = 16 * spec.detail;
  const int columns = 10;
  const float spacing = 2.0f * hx / float(columns + 1), column_h = 7.0f;
  const uint32_t column_mesh = add(column(0.45f, column_h, sides, rings), kBronze, {-hx + spacing, 0.0f, -6.0f});
  const uint32_t arch_mesh =
      add(arch(spacing - 1.17f, 0.5f, 1.17f, 16 * spec.detail), kStone, {-hx + 1.5f * spacing, column_h, -6.0f});
  for (float z : {-6.0f, 6.0f}) {
    for (int c = 0; c < columns; ++c) {
      const glm::vec3 at(-hx + spacing * float(c + 1), 0.0f, z);
      if (!(c == 0 && z < 0.0f)) instance(column_mesh, kBronze, at);
      if (c + 1 < columns && !(c == 0 && z < 0.0f)) instance(arch_mesh, kStone, at + glm::vec3(0.5f * spacing, column_h, 0.0f));
    }
  }
  {
    MeshBuilder gallery;
    const float y = column_h + 0.5f * spacing + 0.2f;
    for (float side : {-1.0f, 1.0f})
      gallery.box({-hx, y, std::min(side * 5.4f, side * hz)}, {hx, y + 0.35f, std::max(side * 5.4f, side * hz)});
    add(gallery.finish("galleries"), kDark);
  }
  scene.lights = {Light{.direction = glm::normalize(glm::vec3(0.35f, 0.8f, 0.5f)), .color = glm::vec3(0.9f, 0.85f, 0.75f)},
                  Light{.kind = Light::Kind::Point, .position = {0.0f, 12.5f, 0.0f}, .color = glm::vec3(0.45f)}};
  scene.ambient = 0.25f;
  const Camera cameras[kAtriumCameras] = {
      {.position = {-19.0f, 2.0f, 0.0f}, .look_at = {10.0f, 4.5f, 0.0f}, .fov_y_degrees = 60.0f},
      {.position = {-17.0f, 12.5f, 4.5f}, .look_at = {8.0f, 0.5f, -3.0f}, .fov_y_degrees = 60.0f},
      {.position = {-18.5f, 1.7f, -9.0f}, .look_at = {15.0f, 3.5f, -5.0f}, .fov_y_degrees = 55.0f},
  };
  scene.camera = cameras[spec.camera];
  check_coordinates(scene);
  return scene;
}

}  // namespace sdfbench
