#include "renderers/sdf/sphere_tracer.h"

#include <algorithm>
#include <limits>
#include <optional>

#include "renderers/frame_params.h"
#include "renderers/sdf/exact_hit.h"
#include "renderers/sdf/triangle_distance.h"
#include "util/error.h"

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

std::string to_string(HitMode hit) {
  switch (hit) {
    case HitMode::exact: return "exact";
    case HitMode::thesis: return "thesis";
    case HitMode::field: return "field";
  }
  return "?";
}

SphereTracer::SphereTracer(const Scene& scene, const SceneSdf& sdf, const SphereTraceParams& params)
    : scene_(scene),
      sdf_(sdf),
      culling_(make_trace_culling(scene, sdf)),
      params_(params),
      epsilon_(params.hit_epsilon * scene_scale(scene)) {}

void SphereTracer::set_frame(const shading::FrameParams& frame) {
  cone_ = params_.footprint * 2.0f * glm::length(glm::vec3(frame.camera_up)) / static_cast<float>(frame.image.y);
}

float SphereTracer::epsilon_at(const shading::Ray& ray, float t) const {
  if (params_.hit == HitMode::thesis) return epsilon_;
  const glm::vec3 p = glm::abs(ray.origin + t * ray.dir);
  return std::max(cone_ * t, 1e-6f * std::max(std::max(p.x, p.y), std::max(p.z, t)));
}

SphereTracer::MarchEnd SphereTracer::march(const shading::Ray& ray, float t1, float& t, uint32_t& steps,
                                           SceneDistance& last, float& t_last, shading::PixelCounts* counts) const {
  const SceneHash& hash = sdf_.hash;
  const glm::vec3 lo = hash.origin, hi = hash.origin + glm::vec3(hash.dims) * hash.cell_size;
  // One epsilon past t1: a step landing a rounding error beyond the box's far face (a wall lying
  // on it) would otherwise end the march in front of the surface.
  // --over-relax (Keinert et al. 2014): a step of omega x the distance is safe when the spheres of
  // the distances at its two ends overlap (their union covers it); when they do not, the march
  // goes back to the previous point, takes its plain step, and steps plainly from then on.
  float omega = params_.over_relax, t_previous = t, plain_previous = 0.0f, previous = 0.0f, step = 0.0f;
  const auto step_back = [&] {
    t = t_previous + plain_previous;
    omega = 1.0f;
    step = 0.0f;
  };
  for (; steps < params_.max_steps; ++steps) {
    const float epsilon = epsilon_at(ray, t);
    if (t > t1 + epsilon) {
      // A relaxed step past the box's far side is unchecked: it may have jumped a surface there.
      if (step > plain_previous) {
        step_back();
        continue;
      }
      return MarchEnd::left;
    }
    // Clamped: the clip's rounding can leave a point a hair outside the box, where a step would
    // be wasted (and wasted differently by the kernels, so the counters would not agree).
    const SceneDistance d = traced_scene_distance(sdf_, scene_, culling_, glm::clamp(ray.origin + t * ray.dir, lo, hi));
    if (counts) {
      (*counts)[COUNTER_STEPS] += 1;
      (*counts)[COUNTER_INSTANCE_EVALS] += d.evaluations;
      (*counts)[COUNTER_TRIANGLE_EVALS] += d.triangle_evaluations;
      (*counts)[COUNTER_AABB_TESTS] += d.box_tests;
    }
    last = d;
    t_last = t;
    if (omega > 1.0f && d.distance + previous < step) {
      step_back();
      continue;
    }
    // A hit needs an exact distance (a listed triangle), not a bound from outside a grid box or
    // from a far cell.
    if (d.distance < epsilon && d.triangle < kFarCellTriangle) {
      ++steps;
      return MarchEnd::converged;
    }
    // At least epsilon: where the ray enters the box, rounding can leave the point a hair
    // outside it, and a bound of ~1e-7 would not move t at all (the ray then stalls to a miss).
    // A far cell's bound is stepped as it is (kFarCellTriangle).
    const float least = d.triangle == kFarCellTriangle ? 0.0f : epsilon;
    const float plain = std::max(d.distance, least);
    step = omega > 1.0f ? std::max(omega * d.distance, least) : plain;
    t_previous = t;
    plain_previous = plain;
    previous = d.distance;
    t += step;
  }
  return t > t1 + epsilon_at(ray, t) ? MarchEnd::left : MarchEnd::out_of_steps;
}

bool SphereTracer::instance_crossing(const shading::Ray& ray, uint32_t instance_id, float t_lo, float t_hi,
                                     Crossing& crossing, shading::PixelCounts* counts) const {
  const Instance& instance = scene_.instances[instance_id];
  const glm::mat4& to_object = sdf_.world_to_object[instance_id];
  const glm::vec3 o(to_object * glm::vec4(ray.origin, 1.0f)), dir(glm::mat3(to_object) * ray.dir);
  uint32_t tests = 0;
  const bool crossed = exact_crossing(sdf_.mesh_grids[instance.mesh], culling_.crossings[instance.mesh],
                                      scene_.meshes[instance.mesh], o, dir, t_lo, t_hi, crossing, tests);
  if (counts) (*counts)[COUNTER_TRIANGLE_TESTS] += tests;
  return crossed;
}

bool SphereTracer::window_crossing(const shading::Ray& ray, float t, float epsilon, uint32_t nearest, SurfaceHit& hit,
                                   shading::PixelCounts* counts) const {
  Crossing crossing;
  bool found = instance_crossing(ray, nearest, t - epsilon, t + epsilon, crossing, counts);
  if (found) hit = SurfaceHit{crossing.t, nearest, crossing.triangle, crossing.uv};
  // The leaf the march evaluated at t lists every instance that can be closest there; the others'
  // surfaces in the window lie in their boxes, and only before the best crossing so far can they win.
  const SceneHash& hash = sdf_.hash;
  const glm::vec3 lo = hash.origin, hi = hash.origin + glm::vec3(hash.dims) * hash.cell_size;
  const glm::vec3 p = glm::clamp(ray.origin + t * ray.dir, lo, hi);  // named: GCC 14 takes a temporary's for a dangling reference
  const OctreeNode& leaf = leaf_at(hash, p);
  for (uint32_t k = 0; k < leaf.list_count; ++k) {
    const uint32_t i = hash.instance_lists[leaf.list_begin + k];
    if (i == nearest) continue;
    if (counts) (*counts)[COUNTER_AABB_TESTS] += 1;
    float s0 = t - epsilon, s1 = found ? hit.t : t + epsilon;
    const Aabb& box = culling_.instance_boxes[i];
    shading::clip_to_box(ray.origin, ray.dir, box.min, box.max, s0, s1);
    if (s0 > s1 || !instance_crossing(ray, i, s0, s1, crossing, counts)) continue;
    // Ties go to the lower instance index, as in the kernel.
    if (!found || crossing.t < hit.t || (crossing.t == hit.t && i < hit.instance)) {
      hit = SurfaceHit{crossing.t, i, crossing.triangle, crossing.uv};
      found = true;
    }
  }
  return found;
}

// --hit thesis: the first converged point. --hit exact: a converged point where the ray crosses
// no listed triangle passed the surface within epsilon (a silhouette), and the march goes on;
// a ray that runs out of steps tests the rest of its segment against the instance nearest to its
// last point, and only then falls back to its first converged point. The search (window_crossing)
// covers one epsilon on either side of the converged point, as far as a step can go, for every
// instance whose surface can lie there, so converging again near the same instance before that
// segment's end needs no second test.
bool SphereTracer::trace(const shading::Ray& ray, float tmax, SurfaceHit& hit, shading::PixelCounts* counts) const {
  const SceneHash& hash = sdf_.hash;
  const glm::vec3 lo = hash.origin, hi = hash.origin + glm::vec3(hash.dims) * hash.cell_size;
  float t = 0.0f, t1 = tmax;  // the ray inside the hash box: outside it there is nothing to hit
  for (int axis = 0; axis < 3; ++axis) {
    const float inv = 1.0f / ray.dir[axis];
    float a = (lo[axis] - ray.origin[axis]) * inv, b = (hi[axis] - ray.origin[axis]) * inv;
    if (a > b) std::swap(a, b);
    t = std::max(t, a);
    t1 = std::min(t1, b);
  }
  if (t > t1) return false;
  const bool exact = params_.hit == HitMode::exact;
  uint32_t steps = 0;
  std::optional<SurfaceHit> first;
  uint32_t cleared_instance = std::numeric_limits<uint32_t>::max();
  float cleared_until = 0.0f;
  SceneDistance d{};
  d.instance = std::numeric_limits<uint32_t>::max();
  float t_last = t;
  MarchEnd end;
  while ((end = march(ray, t1, t, steps, d, t_last, counts)) == MarchEnd::converged) {
    const float epsilon = epsilon_at(ray, t);
    if (exact && (d.instance != cleared_instance || t > cleared_until)) {
      SurfaceHit crossed{};
      if (window_crossing(ray, t, epsilon, d.instance, crossed, counts)) {
        if (crossed.t >= tmax) return false;
        hit = crossed;
        hit.t = std::max(crossed.t, 0.0f);
        return true;
      }
      cleared_instance = d.instance;
      cleared_until = t + epsilon;
    }
    if (!first) first = SurfaceHit{t, d.instance, d.triangle, glm::vec2(0.0f)};
    if (!exact) break;
    t += epsilon;  // the converged distance is below it
  }
  if (end == MarchEnd::out_of_steps) {
    if (counts) (*counts)[COUNTER_OUT_OF_STEPS] += 1;
    // A grazing ray creeping along a surface: the rest of its segment goes to the exact test of
    // the instance nearest to its last point (no surface was crossed before it).
    Crossing crossing;
    if (exact && d.instance != std::numeric_limits<uint32_t>::max() &&
        instance_crossing(ray, d.instance, t_last - epsilon_at(ray, t_last), t1, crossing, counts)) {
      if (crossing.t >= tmax) return false;
      hit = SurfaceHit{std::max(crossing.t, 0.0f), d.instance, crossing.triangle, crossing.uv};
      return true;
    }
  }
  if (!first || (exact && end != MarchEnd::out_of_steps)) return false;
  hit = *first;
  const Instance& instance = scene_.instances[hit.instance];
  const Mesh& mesh = scene_.meshes[instance.mesh];
  const glm::uvec3 tri = mesh.triangles[hit.triangle];
  const glm::vec3 p_local(sdf_.world_to_object[hit.instance] * glm::vec4(ray.origin + hit.t * ray.dir, 1.0f));
  const glm::vec3 a = mesh.positions[tri.x], b = mesh.positions[tri.y], c = mesh.positions[tri.z];
  hit.uv = barycentric(closest_on_triangle(p_local, a, b, c).point, a, b, c);
  return true;
}

bool SphereTracer::closest_hit(shading::Ray ray, float tmax, shading::Hit& hit, shading::PixelCounts* counts) const {
  SurfaceHit surface{};
  if (!trace(ray, tmax, surface, counts)) return false;
  const Instance& instance = scene_.instances[surface.instance];
  const Mesh& mesh = scene_.meshes[instance.mesh];
  const glm::uvec3 tri = mesh.triangles[surface.triangle];
  const glm::vec3 n =
      shading::interpolate_barycentric(mesh.normals[tri.x], mesh.normals[tri.y], mesh.normals[tri.z], surface.uv);
  hit.t = surface.t;
  hit.instance = surface.instance;
  hit.prim = surface.triangle;
  hit.material = instance.material;
  hit.normal = glm::normalize(glm::mat3(instance.transform.object_to_world()) * n);
  hit.uv = surface.uv;
  return true;
}

bool SphereTracer::any_hit(shading::Ray ray, float tmax, shading::PixelCounts* counts) const {
  SurfaceHit surface{};
  return trace(ray, tmax, surface, counts);
}

}  // namespace sdfbench::sdf
