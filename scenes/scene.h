#pragma once
// The scene descriptor every backend consumes (scenes/README.md documents the JSON form).
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scenes/aabb.h"
#include "scenes/implicit.h"
#include "scenes/mesh.h"
#include "scenes/transform.h"

namespace sdfbench {

struct Material {
  std::string name;
  glm::vec3 albedo{0.8f};
  // Checker pattern over the hit's uv (the floor's uv is world x,z): squares of checker_size,
  // alternating albedo and checker_albedo. checker_size 0 disables it.
  float checker_size = 0.0f;
  glm::vec3 checker_albedo{0.2f};
  // Image texture multiplying the albedo, one image repeat per texture_size uv units.
  static constexpr uint32_t kNoTexture = 0xffffffffu;
  uint32_t texture = kNoTexture;  // index into Scene::textures
  float texture_size = 1.0f;
  // With an image texture on a glTF mesh: the first texel, in Scene::texels, of that mesh's
  // per-triangle texture coordinates (scene_texture.h), which then replace the hit's uv. A
  // material with a table is used by instances of that one mesh only.
  uint32_t triangle_uvs = kNoTexture;
  float reflectance = 0.0f;   // mirror weight, used by whitted mode
  float transmission = 0.0f;  // refraction weight, used by whitted mode
  float ior = 1.5f;
};

struct Instance {
  uint32_t mesh = 0;
  uint32_t material = 0;
  Transform transform;
};

struct Light {
  enum class Kind { Directional, Point };
  Kind kind = Kind::Directional;
  glm::vec3 direction{0.0f, 1.0f, 0.0f};  // directional: towards the light, normalised
  glm::vec3 position{0.0f};               // point
  glm::vec3 color{1.0f};
};

struct Camera {
  glm::vec3 position{0.0f, 0.0f, 5.0f};
  glm::vec3 look_at{0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float fov_y_degrees = 45.0f;
};

struct Sky {
  glm::vec3 zenith{0.25f, 0.45f, 0.85f};
  glm::vec3 horizon{0.85f, 0.9f, 1.0f};
};

struct Floor {
  bool enabled = false;
  float height = 0.0f;
  uint32_t material = 0;
};

struct RenderDefaults {
  uint32_t width = 1280;
  uint32_t height = 720;
  uint32_t max_depth = 4;
};

// An image file decoded to linear RGBA; its texels are a slice of Scene::texels.
struct Texture {
  std::filesystem::path source;
  uint32_t first_texel = 0;
  uint32_t width = 0, height = 0;  // row-major, top row first
};

// The largest magnitude of a coordinate a scene may hold, in a mesh's own frame and in the world
// (instances, implicit objects, camera, point lights, floor). Within it every product the kernels
// form stays finite in float: the closest-point test's |edge|^4 (Ericson's degeneracy test,
// barycentrics) reaches (2e9 * sqrt(3))^4 = 1.4e38 < 3.4e38, Möller-Trumbore's |edge|^2 |o - v|
// less; the max ray distance (100 x the scene's diagonal) stays far below the kernels' "no hit"
// sentinels (3e38). Beyond it, squares overflow to inf and slab tests, distances and traversals
// would see inf and NaN.
inline constexpr float kMaxCoordinate = 1e9f;

struct Scene {
  std::string name;  // the descriptor path or generator spec it came from
  std::vector<Mesh> meshes;
  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::vector<glm::vec4> texels;  // every texture's texels, concatenated
  std::vector<Instance> instances;
  // Implicit objects: traced by the shared shading code in every backend; their instance ids
  // follow the meshes' (instances.size() + index).
  std::vector<ImplicitObject> implicits;
  std::vector<Light> lights;
  Camera camera;
  Sky sky;
  Floor floor;
  float ambient = 0.15f;
  RenderDefaults render;

  // World-space bounds of every instance (the floor is unbounded and not included).
  Aabb instance_bounds() const;
  Aabb world_bounds(const Instance& instance) const;
  Aabb world_bounds(const ImplicitObject& object) const;
  Aabb bounds() const;  // instances and implicit objects
  size_t triangle_count() const;  // over all instances
};

// Throws Error (prefixed with scene.name) naming the first mesh (its file), instance, implicit
// object, camera point, point light or floor whose coordinates exceed kMaxCoordinate, with the
// field as a scene file names it (meshes.<name>, instances[i], ...).
void check_coordinates(const Scene& scene);
// The same for one mesh loaded on its own (check-sdf --mesh FILE); `where` prefixes the error.
void check_coordinates(const Mesh& mesh, const std::string& where);

}  // namespace sdfbench
