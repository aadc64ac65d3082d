#include "scenes/overlap_layout.h"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <cmath>
#include <vector>

#include "scenes/named_mesh.h"
#include "scenes/random.h"
#include "scenes/sized_mesh.h"
#include "scenes/thesis_layout.h"
#include "scenes/transform.h"
#include "util/error.h"

namespace sdfbench {
namespace {

constexpr float kThesisRegionVolume = 140.0f * 100.0f * 140.0f;  // thesis_layout.cpp's region, scaled as a whole

std::vector<std::string> split_spec(const std::string& spec) {
  std::vector<std::string> parts;
  for (size_t start = 0;;) {
    const size_t colon = spec.find(':', start);
    parts.push_back(spec.substr(start, colon - start));
    if (colon == std::string::npos) return parts;
    start = colon + 1;
  }
}

}  // namespace

OverlapLayoutSpec parse_overlap_spec(const std::string& spec) {
  const std::vector<std::string> parts = split_spec(spec);
  if (parts.size() < 4 || parts.size() > 5 || parts[0] != "overlap")
    throw Error("scene '" + spec + "': expected overlap:<mesh>:<count>:<k>[:seed], e.g. overlap:bunny:1000:8");
  OverlapLayoutSpec result;
  result.mesh = parts[1];
  if (!is_mesh_name(result.mesh))
    throw Error("scene '" + spec + "': unknown mesh '" + result.mesh + "' (expected " + mesh_names_text() + ")");
  const uint64_t count = parse_spec_integer(parts[2], spec, "count");
  if (count < 1 || count > kMaxThesisCount)
    throw Error("scene '" + spec + "': count must be between 1 and " + std::to_string(kMaxThesisCount));
  result.count = static_cast<uint32_t>(count);
  const std::string& k = parts[3];
  const auto [end, ec] = std::from_chars(k.data(), k.data() + k.size(), result.overlap);
  if (k.empty() || ec != std::errc() || end != k.data() + k.size() || !(result.overlap >= 1 && result.overlap <= kMaxOverlap))
    throw Error("scene '" + spec + "': overlap '" + k + "' is not a number in [1, " + std::to_string(int(kMaxOverlap)) + "]");
  if (parts.size() == 5) result.seed = parse_spec_integer(parts[4], spec, "seed");
  return result;
}

Scene make_overlap_scene(const OverlapLayoutSpec& spec) {
  Scene scene;
  char k[32];
  std::snprintf(k, sizeof k, "%g", spec.overlap);
  scene.name = "overlap:" + spec.mesh + ":" + std::to_string(spec.count) + ":" + k + ":" + std::to_string(spec.seed);
  scene.meshes.push_back(load_named_mesh(spec.mesh));
  add_thesis_materials(scene);
  const Mesh& mesh = scene.meshes[0];
  const float mesh_radius = 0.5f * glm::length(mesh.bounds.extent());
  const glm::vec3 mesh_center = mesh.bounds.center();

  // The thesis' objects (sizes, turns, materials), drawn first: their boxes' summed volume sets
  // the region, scaled from the thesis' so that it is k times smaller than that sum.
  Pcg32 rng(spec.seed);
  std::vector<Instance> instances(spec.count);
  std::vector<glm::vec3> half_extents(spec.count);
  double box_volume = 0;
  for (uint32_t i = 0; i < spec.count; ++i) {
    Instance& instance = instances[i];
    instance.mesh = 0;
    instance.material = (i % 3) * 6 + (i / 3) % 6;
    instance.transform.scale = kThesisBaseRadius * rng.uniform(kThesisMinScale, kThesisMaxScale) / mesh_radius;
    instance.transform.rotation = glm::angleAxis(glm::radians(rng.uniform(0.0f, 360.0f)), glm::vec3(0.0f, 1.0f, 0.0f));
    const Aabb box = transform_box(mesh.bounds, instance.transform.object_to_world());
    half_extents[i] = 0.5f * box.extent();
    box_volume += double(box.extent().x) * box.extent().y * box.extent().z;
  }
  const float scale = static_cast<float>(std::cbrt(box_volume / (spec.overlap * kThesisRegionVolume)));
  const glm::vec3 region_min = glm::vec3(-70.0f, 0.0f, -70.0f) * scale, region_max = glm::vec3(70.0f, 100.0f, 70.0f) * scale;
  for (uint32_t i = 0; i < spec.count; ++i) {
    // Boxes inside the region (where one is wider than the region, centred on it).
    const glm::vec3 lo = glm::min(region_min + half_extents[i], 0.5f * (region_min + region_max));
    const glm::vec3 hi = glm::max(region_max - half_extents[i], lo);
    glm::vec3 center;
    center.x = rng.uniform(lo.x, hi.x);  // separate statements: argument evaluation order is unspecified
    center.y = rng.uniform(lo.y, hi.y);
    center.z = rng.uniform(lo.z, hi.z);
    Instance& instance = instances[i];
    instance.transform.translation = center - instance.transform.scale * (instance.transform.rotation * mesh_center);
    scene.instances.push_back(instance);
  }
  add_thesis_stage(scene, scale);
  return scene;
}

double measured_overlap(const Scene& scene, uint32_t samples) {
  std::vector<Aabb> boxes;
  std::vector<double> cumulative;  // box volumes, summed
  double total = 0;
  for (const Instance& instance : scene.instances) {
    boxes.push_back(scene.world_bounds(instance));
    const glm::vec3 e = boxes.back().extent();
    total += double(e.x) * e.y * e.z;
    cumulative.push_back(total);
  }
  if (boxes.empty() || !(total > 0)) return boxes.empty() ? 0.0 : 1.0;
  Pcg32 rng(1);
  double inverse_sum = 0;
  for (uint32_t s = 0; s < samples; ++s) {
    const double pick = rng.uniform() * total;
    const size_t b = std::min(size_t(std::upper_bound(cumulative.begin(), cumulative.end(), pick) - cumulative.begin()),
                              boxes.size() - 1);
    glm::vec3 p;
    p.x = rng.uniform(boxes[b].min.x, boxes[b].max.x);
    p.y = rng.uniform(boxes[b].min.y, boxes[b].max.y);
    p.z = rng.uniform(boxes[b].min.z, boxes[b].max.z);
    uint32_t count = 0;
    for (const Aabb& box : boxes) count += glm::all(glm::greaterThanEqual(p, box.min)) && glm::all(glm::lessThanEqual(p, box.max));
    inverse_sum += 1.0 / std::max(1u, count);
  }
  return samples / inverse_sum;
}

}  // namespace sdfbench
