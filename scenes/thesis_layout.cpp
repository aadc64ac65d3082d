#include "scenes/thesis_layout.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <vector>

#include <glm/gtc/constants.hpp>

#include "scenes/mesh_resize.h"
#include "scenes/named_mesh.h"
#include "scenes/random.h"
#include "scenes/sized_mesh.h"
#include "util/error.h"

namespace sdfbench {
namespace {

// Thesis chapter 6: objects "condensed in a space of 140 x 100 x 140".
constexpr glm::vec3 kRegionMin{-70.0f, 0.0f, -70.0f};
constexpr glm::vec3 kRegionMax{70.0f, 100.0f, 70.0f};
constexpr int kAttemptsPerObject = 10000;

template <class T>
T parse_number(const std::string& text, const std::string& spec, const char* what) {
  T value{};
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec == std::errc::result_out_of_range && end == text.data() + text.size())
    throw Error("scene '" + spec + "': " + what + " '" + text + "' is out of range (at most " +
                std::to_string(std::numeric_limits<T>::max()) + ")");
  if (ec != std::errc() || end != text.data() + text.size())
    throw Error("scene '" + spec + "': " + what + " '" + text + "' is not a non-negative integer");
  return value;
}

}  // namespace

uint64_t parse_spec_integer(const std::string& text, const std::string& spec, const char* what) {
  return parse_number<uint64_t>(text, spec, what);
}

void add_thesis_materials(Scene& scene) {
  // Instances cycle through them.
  const glm::vec3 palette[6] = {{0.80f, 0.30f, 0.25f}, {0.30f, 0.65f, 0.35f}, {0.30f, 0.45f, 0.85f},
                                {0.85f, 0.75f, 0.30f}, {0.70f, 0.40f, 0.80f}, {0.85f, 0.85f, 0.85f}};
  for (int kind = 0; kind < 3; ++kind) {
    for (int c = 0; c < 6; ++c) {
      Material m;
      m.albedo = palette[c];
      if (kind == 0) m.name = "diffuse_" + std::to_string(c);
      if (kind == 1) m.name = "mirror_" + std::to_string(c), m.reflectance = 0.6f;
      if (kind == 2) m.name = "glass_" + std::to_string(c), m.transmission = 0.8f, m.ior = 1.5f;
      scene.materials.push_back(m);
    }
  }
  Material floor;
  floor.name = "floor_checker";
  floor.albedo = glm::vec3(0.9f);
  floor.checker_albedo = glm::vec3(0.25f);
  floor.checker_size = 20.0f;
  scene.materials.push_back(floor);
}

void add_thesis_stage(Scene& scene, float scale) {
  scene.floor = {.enabled = true, .height = 0.0f, .material = static_cast<uint32_t>(scene.materials.size() - 1)};
  scene.camera = {.position = glm::vec3(0.0f, 75.0f, 150.0f) * scale, .look_at = glm::vec3(0.0f, 40.0f, 0.0f) * scale,
                  .up = {0.0f, 1.0f, 0.0f}, .fov_y_degrees = 55.0f};
  Light sun;
  sun.direction = glm::normalize(glm::vec3(0.4f, 1.0f, 0.3f));
  sun.color = glm::vec3(1.0f);
  scene.lights.push_back(sun);
}

ThesisLayoutSpec parse_thesis_spec(const std::string& spec) {
  std::vector<std::string> parts;
  size_t start = 0;
  while (true) {
    const size_t colon = spec.find(':', start);
    parts.push_back(spec.substr(start, colon - start));
    if (colon == std::string::npos) break;
    start = colon + 1;
  }
  if (parts.size() < 3 || parts.size() > 4 || parts[0] != "thesis")
    throw Error("scene '" + spec + "': expected thesis:<mesh>[@<triangles>]:<count>[:seed], e.g. thesis:bunny:100");
  ThesisLayoutSpec result;
  result.mesh = parts[1];
  if (const size_t at = result.mesh.find('@'); at != std::string::npos) {
    result.triangles = parse_number<uint32_t>(result.mesh.substr(at + 1), spec, "triangle count");
    result.mesh.resize(at);
    if (result.triangles < kMinResizedTriangles || result.triangles > kMaxResizedTriangles)
      throw Error("scene '" + spec + "': triangle count must be between " + std::to_string(kMinResizedTriangles) + " and " +
                  std::to_string(kMaxResizedTriangles));
  }
  if (!is_mesh_name(result.mesh))
    throw Error("scene '" + spec + "': unknown mesh '" + result.mesh + "' (expected " + mesh_names_text() + ")");
  if (result.triangles && builtin_mesh_path(result.mesh).empty())
    throw Error("scene '" + spec + "': a size (@" + std::to_string(result.triangles) + ") is made from a thesis mesh (" +
                "bunny, teapot, monkey, sphere), not from a scan");
  result.count = parse_number<uint32_t>(parts[2], spec, "count");
  if (result.count < 1 || result.count > kMaxThesisCount)
    throw Error("scene '" + spec + "': count must be between 1 and " + std::to_string(kMaxThesisCount));
  if (parts.size() == 4) result.seed = parse_number<uint64_t>(parts[3], spec, "seed");
  return result;
}

Scene make_thesis_scene(const ThesisLayoutSpec& spec) {
  Scene scene;
  std::string mesh_spec = spec.mesh;  // (appended: "@" + std::to_string(n) trips GCC 12's false -Wrestrict, bug 105651)
  if (spec.triangles) mesh_spec.append("@").append(std::to_string(spec.triangles));
  scene.name = "thesis:" + mesh_spec + ":" + std::to_string(spec.count) + ":" + std::to_string(spec.seed);
  scene.meshes.push_back(spec.triangles ? load_sized_mesh(spec.mesh, spec.triangles) : load_named_mesh(spec.mesh));
  add_thesis_materials(scene);
  const Mesh& mesh = scene.meshes[0];
  const float mesh_radius = 0.5f * glm::length(mesh.bounds.extent());
  const glm::vec3 mesh_center = mesh.bounds.center();

  // Beyond 1000 objects the radius shrinks so the packing density stays that of 1000.
  const float base_radius = kThesisBaseRadius * std::min(1.0f, std::cbrt(1000.0f / static_cast<float>(spec.count)));
  Pcg32 rng(spec.seed);
  std::vector<glm::vec4> placed;  // xyz centre, w radius
  for (uint32_t i = 0; i < spec.count; ++i) {
    const float radius = base_radius * rng.uniform(kThesisMinScale, kThesisMaxScale);
    const float yaw = rng.uniform(0.0f, 360.0f);
    glm::vec3 center;
    int attempt = 0;
    for (;; ++attempt) {
      if (attempt == kAttemptsPerObject)
        throw Error("scene '" + scene.name + "': could not place object " + std::to_string(i) + " without overlap");
      // Drawn in x, y, z order as separate statements: argument evaluation order is unspecified.
      center.x = rng.uniform(kRegionMin.x + radius, kRegionMax.x - radius);
      center.y = rng.uniform(kRegionMin.y + radius, kRegionMax.y - radius);
      center.z = rng.uniform(kRegionMin.z + radius, kRegionMax.z - radius);
      const bool overlaps = std::any_of(placed.begin(), placed.end(), [&](const glm::vec4& o) {
        return glm::length(glm::vec3(o) - center) < o.w + radius;
      });
      if (!overlaps) break;
    }
    placed.emplace_back(center, radius);
    Instance instance;
    instance.mesh = 0;
    instance.material = (i % 3) * 6 + (i / 3) % 6;
    instance.transform.scale = radius / mesh_radius;
    instance.transform.rotation = glm::angleAxis(glm::radians(yaw), glm::vec3(0.0f, 1.0f, 0.0f));
    // Put the mesh's bounding-box centre (not its origin) at the sampled centre.
    instance.transform.translation =
        center - instance.transform.scale * (instance.transform.rotation * mesh_center);
    scene.instances.push_back(instance);
  }

  add_thesis_stage(scene, 1.0f);
  return scene;
}

}  // namespace sdfbench
