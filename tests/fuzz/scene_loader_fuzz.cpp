// Fuzz target for the scene descriptor loader (JSON, implicit shapes, and the meshes and images
// it names, resolved beside scenes/ so the committed scenes load). Every input must load as a
// scene the renderers can trust (every index in range: instances' meshes and materials, the
// floor's material, textures and their texels; coordinates within kMaxCoordinate; a usable
// camera) or be refused with sdfbench::Error; anything else (another exception, a crash, a
// sanitizer report, a broken invariant) fails. Built and run like the cache target
// (tests/CMakeLists.txt, fuzz/text_fuzz_driver.cpp).
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "scenes/mesh.h"
#include "scenes/scene_loader.h"
#include "util/error.h"

namespace {

bool within(const glm::vec3& p) {
  return std::abs(p.x) <= sdfbench::kMaxCoordinate && std::abs(p.y) <= sdfbench::kMaxCoordinate &&
         std::abs(p.z) <= sdfbench::kMaxCoordinate;
}

// Why the scene breaks an invariant the renderers rely on, or nothing.
const char* broken(const sdfbench::Scene& s) {
  if (s.materials.empty()) return "no material";
  for (const sdfbench::Instance& i : s.instances) {
    if (i.mesh >= s.meshes.size()) return "an instance's mesh index";
    if (i.material >= s.materials.size()) return "an instance's material index";
    if (!(i.transform.scale > 0.0f) || !within(i.transform.translation)) return "an instance's transform";
  }
  for (const sdfbench::Mesh& m : s.meshes) {
    if (m.triangles.empty() || m.normals.size() != m.positions.size()) return "a mesh's triangles or normals";
    for (const glm::vec3& p : m.positions)
      if (!within(p)) return "a mesh position";
    for (const glm::uvec3& t : m.triangles)
      if (t.x >= m.positions.size() || t.y >= m.positions.size() || t.z >= m.positions.size()) return "a triangle index";
  }
  for (const sdfbench::Material& m : s.materials) {
    if (m.texture == sdfbench::Material::kNoTexture) continue;
    if (m.texture >= s.textures.size()) return "a material's texture index";
    const sdfbench::Texture& t = s.textures[m.texture];
    if (uint64_t(t.first_texel) + uint64_t(t.width) * t.height > s.texels.size()) return "a texture's texels";
    if (!(m.texture_size > 0.0f)) return "a texture's size";
  }
  if (s.floor.enabled && s.floor.material >= s.materials.size()) return "the floor's material";
  if (!within(s.camera.position) || !within(s.camera.look_at) || s.camera.position == s.camera.look_at) return "the camera";
  if (!(s.camera.fov_y_degrees > 0.0f && s.camera.fov_y_degrees < 180.0f)) return "the camera's field of view";
  for (const sdfbench::Light& l : s.lights)
    if (!within(l.position) || !std::isfinite(l.direction.x) || !std::isfinite(l.color.x)) return "a light";
  return nullptr;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::filesystem::path origin = sdfbench::data_dir() / "fuzz.json";
  try {
    const sdfbench::Scene scene = sdfbench::parse_scene_json(std::string(reinterpret_cast<const char*>(data), size), origin);
    if (const char* why = broken(scene)) {
      std::fprintf(stderr, "FAIL: an accepted scene breaks an invariant: %s\n", why);
      std::abort();
    }
  } catch (const sdfbench::Error&) {
  }
  return 0;
}
