#include "renderers/sdf/sphere_tracer.h"

#include <algorithm>
#include <limits>

#include "renderers/frame_params.h"
#include "renderers/sdf/triangle_distance.h"

namespace sdfbench::sdf {
namespace {

// Barycentric (u, v) of a point in triangle abc with p = (1 - u - v) a + u b + v c.
glm::vec2 barycentric(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  const glm::vec3 v0 = b - a, v1 = c - a, v2 = p - a;
  const float d00 = glm::dot(v0, v0), d01 = glm::dot(v0, v1), d11 = glm::dot(v1, v1);
  const float d20 = glm::dot(v2, v0), d21 = glm::dot(v2, v1);
  const float denom = d00 * d11 - d01 * d01;
  if (denom == 0.0f) return glm::vec2(0.0f);
  return glm::vec2((d11 * d20 - d01 * d21) / denom, (d00 * d21 - d01 * d20) / denom);
}

}  // namespace

SphereTracer::SphereTracer(const Scene& scene, const SceneSdf& sdf, const SphereTraceParams& params)
    : scene_(scene),
      sdf_(sdf),
      culling_(make_trace_culling(scene, sdf)),
      params_(params),
      epsilon_(params.hit_epsilon * scene_scale(scene)) {}

float SphereTracer::march(const shading::Ray& ray, float tmax, SceneDistance& at_hit, shading::PixelCounts* counts) const {
  const SceneHash& hash = sdf_.hash;
  // Clip to the hash box: outside it there is nothing to hit.
  const glm::vec3 lo = hash.origin, hi = hash.origin + glm::vec3(hash.dims) * hash.cell_size;
  float t0 = 0.0f, t1 = tmax;
  for (int axis = 0; axis < 3; ++axis) {
    const float inv = 1.0f / ray.dir[axis];
    float a = (lo[axis] - ray.origin[axis]) * inv, b = (hi[axis] - ray.origin[axis]) * inv;
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
  }
  if (t0 > t1) return -1.0f;
  float t = t0;
  for (uint32_t step = 0; step < params_.max_steps && t <= t1; ++step) {
    // Clamped: the clip's rounding can leave a point a hair outside the box, where a step would
    // be wasted (and wasted differently by the kernels, so the counters would not agree).
    const SceneDistance d = traced_scene_distance(sdf_, scene_, culling_, glm::clamp(ray.origin + t * ray.dir, lo, hi));
    if (counts) {
      (*counts)[COUNTER_STEPS] += 1;
      (*counts)[COUNTER_INSTANCE_EVALS] += d.evaluations;
      (*counts)[COUNTER_TRIANGLE_EVALS] += d.triangle_evaluations;
      (*counts)[COUNTER_AABB_TESTS] += d.box_tests;
    }
    // A hit needs an exact distance (a listed triangle), not a bound from outside a grid box.
    if (d.distance < epsilon_ && d.triangle != std::numeric_limits<uint32_t>::max()) {
      at_hit = d;
      return t;
    }
    // At least epsilon: where the ray enters the box, rounding can leave the point a hair
    // outside it, and a bound of ~1e-7 would not move t at all (the ray then stalls to a miss).
    t += std::max(d.distance, epsilon_);
  }
  return -1.0f;
}

bool SphereTracer::closest_hit(shading::Ray ray, float tmax, shading::Hit& hit, shading::PixelCounts* counts) const {
  SceneDistance d{};
  const float t = march(ray, tmax, d, counts);
  if (t < 0.0f) return false;
  const Instance& instance = scene_.instances[d.instance];
  const Mesh& mesh = scene_.meshes[instance.mesh];
  const glm::uvec3 tri = mesh.triangles[d.triangle];
  const glm::vec3 p_local(instance.transform.world_to_object() * glm::vec4(ray.origin + t * ray.dir, 1.0f));
  const glm::vec3 a = mesh.positions[tri.x], b = mesh.positions[tri.y], c = mesh.positions[tri.z];
  const glm::vec2 uv = barycentric(closest_on_triangle(p_local, a, b, c).point, a, b, c);
  const glm::vec3 n = shading::interpolate_barycentric(mesh.normals[tri.x], mesh.normals[tri.y], mesh.normals[tri.z], uv);
  hit.t = t;
  hit.instance = d.instance;
  hit.prim = d.triangle;
  hit.material = instance.material;
  hit.normal = glm::normalize(glm::mat3(instance.transform.object_to_world()) * n);
  hit.uv = uv;
  return true;
}

bool SphereTracer::any_hit(shading::Ray ray, float tmax, shading::PixelCounts* counts) const {
  SceneDistance d{};
  return march(ray, tmax, d, counts) >= 0.0f;
}

}  // namespace sdfbench::sdf
