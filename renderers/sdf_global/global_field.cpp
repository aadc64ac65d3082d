#include "renderers/sdf_global/global_field.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <span>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "renderers/sdf/scene_hash.h"
#include "util/error.h"
#include "util/input_file.h"
#include "util/progress.h"

namespace sdfbench::sdf {
namespace {

size_t index_of(const glm::uvec3& c, const glm::uvec3& dims) { return c.x + size_t(dims.x) * (c.y + size_t(dims.y) * c.z); }
glm::uvec3 coords_of(size_t i, const glm::uvec3& dims) {
  return glm::uvec3(i % dims.x, (i / dims.x) % dims.y, i / (size_t(dims.x) * dims.y));
}

float box_distance(const Aabb& box, const glm::vec3& p) {
  return glm::length(glm::max(glm::max(box.min - p, p - box.max), glm::vec3(0.0f)));
}

// Where the samples come from: per mesh its grid, or where the band reaches beyond the grid's box
// the exact distance there too; and the instances' frames.
struct SamplingGrids {
  std::vector<const MeshDistanceGrid*> grids;        // per mesh
  std::vector<std::optional<ExactMeshDistance>> exact;  // per mesh, where the band reaches beyond its grid
  const std::vector<glm::mat4>* world_to_object;
};

// One instance's signed distance at world point p (a lower bound in magnitude outside its grid box
// unless the mesh has an exact query). Where the exact query answers, a surface farther than
// `bound` may read as +infinity (ExactMeshDistance).
float signed_instance_distance(const Scene& scene, const SamplingGrids& sampling, uint32_t i, const glm::vec3& p,
                               float bound = std::numeric_limits<float>::infinity()) {
  const Instance& instance = scene.instances[i];
  const glm::vec3 local((*sampling.world_to_object)[i] * glm::vec4(p, 1.0f));
  const std::optional<ExactMeshDistance>& exact = sampling.exact[instance.mesh];
  // The bound in object space, a little wider so that rounding never drops a surface at it.
  const float d = exact ? exact->signed_distance(local, bound / instance.transform.scale * 1.001f)
                        : grid_signed_distance(*sampling.grids[instance.mesh], scene.meshes[instance.mesh], local);
  return d * instance.transform.scale;
}

// The composite over `candidates`: the least magnitude, negative inside any of them (so that its
// magnitude is the distance to the union of the surfaces, never more). Instances whose box is
// farther than the best so far are skipped (their surface lies in their box), and the best so far
// bounds each exact query. Where every surface is farther than `cap`, the value is `cap` (a
// sample clamped to the band needs no more).
struct Composite {
  float value = std::numeric_limits<float>::max();
  bool inside = false;
};
template <class Candidates>
Composite composite(const Scene& scene, const SamplingGrids& sampling, const std::vector<Aabb>& boxes, const Candidates& candidates,
                    const glm::vec3& p, float cap = std::numeric_limits<float>::max()) {
  Composite c;
  c.value = cap;
  for (uint32_t i : candidates) {
    const float box = box_distance(boxes[i], p);
    if (box > 0.0f && box >= c.value) continue;  // outside its box: farther than the best, and not inside it
    const float d = signed_instance_distance(scene, sampling, i, p, c.value);
    c.value = std::min(c.value, std::abs(d));
    c.inside = c.inside || d < 0.0f;
  }
  return c;
}

float signed_value(const Composite& c) { return c.inside ? -c.value : c.value; }

}  // namespace

void validate(const GlobalFieldParams& params) {
  // The builder's domain, for a record made in code (tests). The flags' ranges are their
  // declarations' (sdf_global_renderer.cpp, brick_field_tables.cpp; checked where a value is
  // parsed), and a cache file's values are checked where they are decoded (global_field_codec.cpp).
  if (!(params.voxel >= 0.0f) || !std::isfinite(params.voxel) || params.band < 1 || params.band > 16)
    throw InternalError("a global field of voxel " + std::to_string(params.voxel) + " (0: auto) and band " +
                        std::to_string(params.band) + " (the voxel must be finite and >= 0, the band from 1 to 16 voxels)");
}

float auto_global_voxel(const Scene& scene) {
  std::vector<float> extents;
  for (const Instance& instance : scene.instances) {
    const glm::vec3 e = scene.world_bounds(instance).extent();
    extents.push_back(std::max({e.x, e.y, e.z}));
  }
  if (extents.empty()) return 1.0f;
  std::nth_element(extents.begin(), extents.begin() + extents.size() / 2, extents.end());
  const glm::vec3 scene_extent = scene.instance_bounds().extent();
  const float largest = std::max({scene_extent.x, scene_extent.y, scene_extent.z});
  return std::max(extents[extents.size() / 2] / kAutoVoxelsPerInstance, largest / float(kMaxGlobalCells));
}

float global_field_voxel(const Scene& scene, const GlobalFieldParams& params) {
  const glm::vec3 extent = scene.instance_bounds().extent();
  const float largest = std::max({extent.x, extent.y, extent.z});
  const float voxel = params.voxel > 0.0f ? params.voxel : auto_global_voxel(scene);
  return std::max(voxel, 1e-6f * std::max(largest, 1e-30f));  // a size float can step by
}

GlobalField build_global_field(const Scene& scene, const SceneSdf& scene_sdf, const MeshGridParams& mesh_params,
                               const GlobalFieldParams& params) {
  validate(params);
  const auto start = std::chrono::steady_clock::now();
  GlobalField global;
  global.voxel_request = params.voxel;
  BrickField& field = global.field;
  if (scene.instances.empty()) {  // (implicit objects only) one empty brick, far from everything
    field.voxel = 1.0f;
    field.bricks = glm::uvec3(1u);
    field.format = params.format;
    field.band = static_cast<float>(params.band);
    field.quantization = brick_quantization(params.format, field.band);
    field.indirection = {kEmptyBrick};
    field.coarse_at_centres = true;
    field.coarse = {1e30f};
    global.list_begin = {0};
    return global;
  }
  const uint32_t instance_count = static_cast<uint32_t>(scene.instances.size());
  std::vector<Aabb> boxes;
  for (const Instance& instance : scene.instances) boxes.push_back(scene.world_bounds(instance));

  const Aabb scene_box = scene.instance_bounds();
  const glm::vec3 extent = scene_box.extent();
  field.voxel = global_field_voxel(scene, params);
  field.format = params.format;
  field.band = static_cast<float>(params.band) * field.voxel;
  field.quantization = brick_quantization(params.format, field.band);
  const float margin = static_cast<float>(params.band + 1) * field.voxel;
  field.origin = scene_box.min - margin;
  const glm::vec3 cells = glm::ceil((extent + 2.0f * margin) / field.voxel);
  const glm::vec3 bricks = glm::ceil(cells / float(kBrickCells));
  const double brick_count_d = double(bricks.x) * bricks.y * bricks.z;
  if (brick_count_d > double(kMaxHashCells))
    throw Error("sdf-global: --global-voxel " + std::to_string(field.voxel) + " would need " +
                std::to_string(uint64_t(brick_count_d)) + " bricks over the scene (at most " + std::to_string(kMaxHashCells) +
                "); use a larger --global-voxel");
  // What the build holds per brick before any brick is sampled (candidate offsets, stored flag,
  // list vector, indirection, coarse value), bounded here: the later checks come after it is
  // allocated (2^26 bricks are 2.7 GB of it).
  constexpr uint64_t kBookkeepingBytesPerBrick = sizeof(uint64_t) + sizeof(uint8_t) + sizeof(std::vector<uint32_t>) +
                                                 sizeof(uint32_t) + sizeof(float);
  if (brick_count_d * kBookkeepingBytesPerBrick > double(params.max_bytes))
    throw Error("sdf-global: --global-voxel " + std::to_string(field.voxel) + " would need " +
                std::to_string(uint64_t(brick_count_d)) + " bricks over the scene, " +
                describe_bytes(uint64_t(brick_count_d) * kBookkeepingBytesPerBrick) +
                " of bookkeeping to build them, more than --max-structure-mb allows (" +
                std::to_string(params.max_bytes >> 20) + "); use a larger --global-voxel or raise --max-structure-mb");
  field.bricks = glm::uvec3(bricks);
  const size_t brick_count = size_t(brick_count_d);
  const float brick_size = float(kBrickCells) * field.voxel;
  const float reach = 0.5f * brick_size * std::sqrt(3.0f);
  const glm::vec3 lattice_max = field.box_max();
  const float coordinate_slack = 1e-4f * std::max({glm::length(field.origin), glm::length(lattice_max), 1e-30f});
  const float list_slack = kListSlackVoxels * field.voxel + coordinate_slack;

  // Exact samples within the band of every instance: where the band reaches beyond a mesh grid's
  // box (its instances' smallest scale sets the reach), the exact distance there too.
  std::vector<float> smallest_scale(scene.meshes.size(), std::numeric_limits<float>::max());
  for (const Instance& instance : scene.instances)
    smallest_scale[instance.mesh] = std::min(smallest_scale[instance.mesh], instance.transform.scale);
  SamplingGrids sampling{{}, {}, &scene_sdf.world_to_object};
  sampling.exact.resize(scene.meshes.size());
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const MeshDistanceGrid& grid = scene_sdf.mesh_grids[m];
    sampling.grids.push_back(&grid);
    if (smallest_scale[m] == std::numeric_limits<float>::max()) continue;  // no instance
    const float reach_cells = (field.band + 2.0f * field.voxel) / smallest_scale[m] / grid.cell_size;
    if (!(reach_cells + 1.0f > mesh_params.margin_cells)) continue;  // the band stays in the grid's box
    sampling.exact[m].emplace(grid, scene.meshes[m]);
  }

  // Candidates per brick: the instances whose box comes within the band (or the list slack) of it;
  // no other can give a value below the band there.
  const float candidate_reach = std::max(field.band, list_slack) + field.voxel;
  auto brick_range = [&](const Aabb& box, glm::uvec3& lo, glm::uvec3& hi) {
    const glm::vec3 a = glm::floor((box.min - candidate_reach - field.origin) / brick_size);
    const glm::vec3 b = glm::floor((box.max + candidate_reach - field.origin) / brick_size);
    lo = glm::uvec3(glm::clamp(a, glm::vec3(0.0f), glm::vec3(field.bricks - 1u)));
    hi = glm::uvec3(glm::clamp(b, glm::vec3(0.0f), glm::vec3(field.bricks - 1u)));
  };
  // CSR: counts, prefix sums, fill.
  std::vector<uint64_t> candidate_begin(brick_count + 1, 0);
  for (const Aabb& box : boxes) {
    glm::uvec3 lo, hi;
    brick_range(box, lo, hi);
    for (uint32_t z = lo.z; z <= hi.z; ++z)
      for (uint32_t y = lo.y; y <= hi.y; ++y)
        for (uint32_t x = lo.x; x <= hi.x; ++x) ++candidate_begin[index_of({x, y, z}, field.bricks) + 1];
  }
  for (size_t b = 0; b < brick_count; ++b) candidate_begin[b + 1] += candidate_begin[b];
  if (candidate_begin[brick_count] * sizeof(uint32_t) > params.max_bytes)
    throw Error("sdf-global: the field's candidate lists would need " + describe_bytes(candidate_begin[brick_count] * 4) +
                ", more than --max-structure-mb allows; use a larger --global-voxel");
  std::vector<uint32_t> candidates(candidate_begin[brick_count]);
  {
    std::vector<uint64_t> next(candidate_begin.begin(), candidate_begin.end() - 1);
    for (uint32_t i = 0; i < instance_count; ++i) {
      glm::uvec3 lo, hi;
      brick_range(boxes[i], lo, hi);
      for (uint32_t z = lo.z; z <= hi.z; ++z)
        for (uint32_t y = lo.y; y <= hi.y; ++y)
          for (uint32_t x = lo.x; x <= hi.x; ++x) candidates[next[index_of({x, y, z}, field.bricks)]++] = i;
    }
  }
  auto candidates_of = [&](size_t b) {
    return std::span<const uint32_t>(candidates.data() + candidate_begin[b], candidates.data() + candidate_begin[b + 1]);
  };

  // Which bricks are stored (a point of it may come within the band) and which instances each lists.
  std::vector<uint8_t> stored(brick_count, 0);
  std::vector<std::vector<uint32_t>> lists(brick_count);
  const float relevant = reach + std::max(field.band, list_slack);  // farther: neither listed nor stored for it
  tbb::parallel_for(tbb::blocked_range<size_t>(0, brick_count), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t b = r.begin(); b != r.end(); ++b) {
      const auto cands = candidates_of(b);
      if (cands.empty()) continue;
      const glm::vec3 centre = field.origin + brick_size * (glm::vec3(coords_of(b, field.bricks)) + 0.5f);
      float nearest = std::numeric_limits<float>::max();
      for (uint32_t i : cands) {
        if (box_distance(boxes[i], centre) > relevant) continue;
        const float d = std::abs(signed_instance_distance(scene, sampling, i, centre, relevant));
        nearest = std::min(nearest, d);
        if (d - reach <= list_slack) lists[b].push_back(i);
      }
      stored[b] = nearest - reach < field.band || !lists[b].empty();
    }
  });
  field.indirection.assign(brick_count, kEmptyBrick);
  uint32_t next_slot = 0;
  global.list_begin.push_back(0);
  for (size_t b = 0; b < brick_count; ++b) {
    if (!stored[b]) continue;
    field.indirection[b] = next_slot++;
    global.list_instances.insert(global.list_instances.end(), lists[b].begin(), lists[b].end());
    global.list_begin.push_back(static_cast<uint32_t>(global.list_instances.size()));
    std::vector<uint32_t>().swap(lists[b]);
  }
  const size_t sample_bytes = bytes_per_sample(params.format);
  const uint64_t atlas_bytes = uint64_t(next_slot) * kBrickSamples * sample_bytes;
  const uint64_t total = atlas_bytes + uint64_t(brick_count) * 4 + uint64_t(global.list_instances.size()) * 4;
  if (total > params.max_bytes)
    throw Error("sdf-global: the field would need " + describe_bytes(total) + " (" + std::to_string(next_slot) +
                " bricks at --global-voxel " + std::to_string(field.voxel) +
                "), more than --max-structure-mb allows; use a larger --global-voxel, a narrower --brick-band or "
                "--sdf-format f16/u8");
  field.atlas.resize(atlas_bytes);

  // Coarse level, one value per brick: a lower bound on the distance from its centre to the
  // nearest surface (exact over the brick's candidates, the box distance of every other instance),
  // so that an empty brick's step costs one fetch (brick_sample.glsl). Unclamped: far from
  // everything it is the step.
  field.coarse_at_centres = true;
  field.coarse.resize(brick_count);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, brick_count), [&](const tbb::blocked_range<size_t>& r) {
    std::vector<uint8_t> is_candidate(instance_count, 0);
    for (size_t b = r.begin(); b != r.end(); ++b) {
      const glm::vec3 centre = field.origin + brick_size * (glm::vec3(coords_of(b, field.bricks)) + 0.5f);
      const auto cands = candidates_of(b);
      Composite c = composite(scene, sampling, boxes, cands, centre);
      for (uint32_t i : cands) is_candidate[i] = 1;
      for (uint32_t i = 0; i < instance_count; ++i)
        if (!is_candidate[i]) c.value = std::min(c.value, box_distance(boxes[i], centre));
      for (uint32_t i : cands) is_candidate[i] = 0;
      field.coarse[b] = c.value;
    }
  });

  ProgressMeter progress("global field (" + std::to_string(next_slot) + " bricks)", brick_count, "bricks");
  tbb::parallel_for(tbb::blocked_range<size_t>(0, brick_count), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t b = r.begin(); b != r.end(); ++b) {
      if (field.indirection[b] == kEmptyBrick) continue;
      const glm::uvec3 c = coords_of(b, field.bricks);
      const auto cands = candidates_of(b);
      uint8_t* out = &field.atlas[size_t(field.indirection[b]) * kBrickSamples * sample_bytes];
      for (uint32_t z = 0; z < kBrickSide; ++z)
        for (uint32_t y = 0; y < kBrickSide; ++y)
          for (uint32_t x = 0; x < kBrickSide; ++x, out += sample_bytes) {
            const glm::vec3 p = field.origin + field.voxel * glm::vec3(c * kBrickCells + glm::uvec3(x, y, z));
            store_sample(params.format, field.band, signed_value(composite(scene, sampling, boxes, cands, p, field.band)), out);
          }
    }
    progress.advance(r.size());
  });
  field.build_ms = global.build_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return global;
}

}  // namespace sdfbench::sdf
