#include "scenes/scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <string>

#include "util/error.h"


namespace sdfbench {

Aabb Scene::world_bounds(const Instance& instance) const {
  return transform_box(meshes[instance.mesh].bounds, instance.transform.object_to_world());
}

Aabb Scene::world_bounds(const ImplicitObject& object) const {
  return transform_box(implicit_bounds(object.nodes), object.transform.object_to_world());
}

Aabb Scene::instance_bounds() const {
  Aabb bounds;
  for (const Instance& instance : instances) bounds.extend(world_bounds(instance));
  return bounds;
}

Aabb Scene::bounds() const {
  Aabb bounds = instance_bounds();
  for (const ImplicitObject& object : implicits) bounds.extend(world_bounds(object));
  return bounds;
}

size_t Scene::triangle_count() const {
  size_t count = 0;
  for (const Instance& instance : instances) count += meshes[instance.mesh].triangle_count();
  return count;
}

namespace {

// The largest magnitude among the points' coordinates; inf when one is not finite.
float largest_coordinate(std::initializer_list<glm::vec3> points) {
  float largest = 0.0f;
  for (const glm::vec3& p : points)
    for (int k = 0; k < 3; ++k) largest = std::isfinite(p[k]) ? std::max(largest, std::abs(p[k])) : INFINITY;
  return largest;
}

std::string short_float(float v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", static_cast<double>(v));
  return text;
}

void require_within(const std::string& where, std::initializer_list<glm::vec3> points, const std::string& what) {
  const float largest = largest_coordinate(points);
  if (largest <= kMaxCoordinate) return;
  throw Error(where + ": " + what + " reaches a coordinate of " + short_float(largest) + ", beyond the limit of " +
              short_float(kMaxCoordinate) + " in magnitude (docs/limits.md \"Inputs, outputs and limits\")");
}

}  // namespace

void check_coordinates(const Mesh& mesh, const std::string& where) {
  require_within(where, {mesh.bounds.min, mesh.bounds.max}, "mesh '" + mesh.name + "' (file '" + mesh.source.string() + "')");
}

void check_coordinates(const Scene& scene) {
  // Meshes and shapes first: with their own coordinates within the limit (and the transforms'
  // bounded scale and translation), their world boxes are finite.
  for (const Mesh& mesh : scene.meshes)
    require_within(scene.name, {mesh.bounds.min, mesh.bounds.max}, "meshes." + mesh.name + " (file '" + mesh.source.string() + "')");
  for (size_t i = 0; i < scene.implicits.size(); ++i) {
    const Aabb shape = implicit_bounds(scene.implicits[i].nodes);
    require_within(scene.name, {shape.min, shape.max}, "implicits[" + std::to_string(i) + "].shape");
  }
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    const Aabb box = scene.world_bounds(scene.instances[i]);
    require_within(scene.name, {box.min, box.max}, "instances[" + std::to_string(i) + "] (its mesh scaled and moved)");
  }
  for (size_t i = 0; i < scene.implicits.size(); ++i) {
    const Aabb box = scene.world_bounds(scene.implicits[i]);
    require_within(scene.name, {box.min, box.max}, "implicits[" + std::to_string(i) + "] (its shape scaled and moved)");
  }
  require_within(scene.name, {scene.camera.position}, "camera.position");
  require_within(scene.name, {scene.camera.look_at}, "camera.look_at");
  for (size_t i = 0; i < scene.lights.size(); ++i)
    if (scene.lights[i].kind == Light::Kind::Point)
      require_within(scene.name, {scene.lights[i].position}, "lights[" + std::to_string(i) + "].position");
  if (scene.floor.enabled) require_within(scene.name, {glm::vec3(0.0f, scene.floor.height, 0.0f)}, "floor.height");
}

}  // namespace sdfbench
