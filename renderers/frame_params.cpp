#include "renderers/frame_params.h"

#include <algorithm>
#include <cmath>

#include "renderers/implicit_tables.h"

namespace sdfbench {
namespace {

constexpr float kMaxRayDistanceScales = 100.0f;  // the max ray distance is this x the scene scale

double box_distance(const Aabb& box, const glm::vec3& p) {
  const glm::dvec3 d = glm::max(glm::max(glm::dvec3(box.min) - glm::dvec3(p), glm::dvec3(p) - glm::dvec3(box.max)), glm::dvec3(0.0));
  return glm::length(d);
}

}  // namespace

// The diagonal of the box around the camera and the objects, nearest first, stopping at the
// first object beyond the max ray distance of what was gathered before it (100 x the larger of
// that box's diagonal and the camera's distance to its look-at point). For a scene whose objects
// lie together (every committed one) that is all of them with the camera, as before; an object
// far away (translate 1e6) lies beyond every ray and no longer inflates the hit epsilons and the
// max ray distance of the objects one sees.
float scene_scale(const Scene& scene) {
  std::vector<std::pair<double, Aabb>> objects;  // (distance from the camera, world box)
  const glm::vec3 eye = scene.camera.position;
  for (const Instance& instance : scene.instances) objects.emplace_back(0.0, scene.world_bounds(instance));
  for (const ImplicitObject& object : scene.implicits) objects.emplace_back(0.0, scene.world_bounds(object));
  for (auto& [distance, box] : objects) distance = box_distance(box, eye);
  std::stable_sort(objects.begin(), objects.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  const double view = glm::length(glm::dvec3(scene.camera.look_at) - glm::dvec3(eye));
  Aabb bounds;
  bounds.extend(eye);
  for (size_t i = 0; i < objects.size(); ++i) {
    const double reach = kMaxRayDistanceScales * std::max<double>(glm::length(bounds.extent()), view);
    if (i > 0 && objects[i].first > reach) break;  // the nearest object always counts
    bounds.extend(objects[i].second);
  }
  return std::max(1e-3f, glm::length(bounds.extent()));
}

ShadingInputs make_shading_inputs(const Scene& scene, const FrameRequest& request) {
  using glm::vec4;
  ShadingInputs in{};
  const Camera& cam = scene.camera;
  const glm::vec3 forward = glm::normalize(cam.look_at - cam.position);
  const glm::vec3 right = glm::normalize(glm::cross(forward, cam.up));
  const glm::vec3 up = glm::cross(right, forward);
  const float tan_half = std::tan(glm::radians(cam.fov_y_degrees) * 0.5f);
  const float aspect = static_cast<float>(request.width) / static_cast<float>(request.height);
  const float scale = scene_scale(scene);

  shading::FrameParams& f = in.frame;
  f.camera_origin = vec4(cam.position, 1.0f);
  f.camera_forward = vec4(forward, 0.0f);
  f.camera_right = vec4(right * tan_half * aspect, 0.0f);
  f.camera_up = vec4(up * tan_half, 0.0f);
  f.sky_zenith = vec4(scene.sky.zenith, 0.0f);
  f.sky_horizon = vec4(scene.sky.horizon, 0.0f);
  f.floor = vec4(scene.floor.height, static_cast<float>(scene.floor.material), scene.floor.enabled ? 1.0f : 0.0f, 0.0f);
  // Implicit objects' hit epsilon (w): the SDF backends' thesis hit epsilon, 5e-6 x the scene
  // scale. Rays leave surfaces by offset_origin() in shading.glsl, which follows the hit.
  f.tracing = vec4(0.0f, scene.ambient, kMaxRayDistanceScales * scale, 5e-6f * scale);
  f.image = glm::uvec4(request.width, request.height, static_cast<uint32_t>(request.mode),
                       static_cast<uint32_t>(scene.lights.size()));
  ImplicitTables implicits = make_implicit_tables(scene);
  f.limits = glm::uvec4(request.max_depth.value_or(scene.render.max_depth), implicits.objects.size(), 0u, 0u);
  in.implicit_objects = std::move(implicits.objects);
  in.implicit_nodes = std::move(implicits.nodes);

  for (const Material& m : scene.materials) {
    shading::GpuMaterial g{};
    g.albedo = vec4(m.albedo, m.checker_size);
    g.checker_albedo = vec4(m.checker_albedo, 0.0f);
    g.optics = vec4(m.reflectance, m.transmission, m.ior, 0.0f);
    g.image_texture.w = shading::NO_UV_TABLE_VALUE;
    if (m.texture != Material::kNoTexture) {
      const Texture& t = scene.textures[m.texture];
      g.checker_albedo.w = m.texture_size;
      g.image_texture = glm::uvec4(t.first_texel, t.width, t.height,
                                   m.triangle_uvs == Material::kNoTexture ? shading::NO_UV_TABLE_VALUE : m.triangle_uvs);
    }
    in.materials.push_back(g);
  }
  for (const Light& l : scene.lights) {
    shading::GpuLight g{};
    g.position = l.kind == Light::Kind::Directional ? vec4(l.direction, 0.0f) : vec4(l.position, 1.0f);
    g.color = vec4(l.color, 0.0f);
    in.lights.push_back(g);
  }
  if (in.lights.empty()) in.lights.push_back(shading::GpuLight{});
  return in;
}

}  // namespace sdfbench
