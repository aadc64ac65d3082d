#include "renderers/sdf/scene_hash.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <functional>
#include <numeric>

#include <tbb/parallel_invoke.h>

#include "util/error.h"
#include "util/number_text.h"
#include "util/input_file.h"
#include "util/progress.h"

namespace sdfbench::sdf {
namespace {

constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();

float box_distance(const Aabb& box, const glm::vec3& p) {
  const glm::vec3 d = glm::max(glm::max(box.min - p, p - box.max), glm::vec3(0.0f));
  return glm::length(d);
}

// Bounds of one instance's distance at a point, for the exact list rule.
class InstanceBounds {
 public:
  InstanceBounds(const Scene& scene, const std::vector<MeshDistanceGrid>& grids) : scene_(scene), grids_(grids) {
    for (const Instance& instance : scene.instances) {
      world_box_.push_back(scene.world_bounds(instance));
      world_to_object_.push_back(instance.transform.world_to_object());
    }
  }
  // Cheap lower bound: the surface lies inside the instance's world AABB.
  float box_lower(uint32_t i, const glm::vec3& p) const { return box_distance(world_box_[i], p); }
  // Grid lower bound: exact inside the mesh grid box, distance to the box outside.
  float grid_lower(uint32_t i, const glm::vec3& p) const {
    const Instance& instance = scene_.instances[i];
    const glm::vec3 local(world_to_object_[i] * glm::vec4(p, 1.0f));
    return grid_distance(grids_[instance.mesh], scene_.meshes[instance.mesh], local) * instance.transform.scale;
  }
  // Upper bound: outside the grid box, |p - q| + d(q) with q the nearest point of the box
  // (triangle inequality; d(q) is exact since q is inside, or an upper bound in a far cell).
  float upper(uint32_t i, const glm::vec3& p) const {
    const Instance& instance = scene_.instances[i];
    const MeshDistanceGrid& grid = grids_[instance.mesh];
    const glm::vec3 local(world_to_object_[i] * glm::vec4(p, 1.0f));
    const glm::vec3 hi = grid.origin + glm::vec3(grid.dims) * grid.cell_size;
    const glm::vec3 q = glm::clamp(local, grid.origin, hi);
    const float d = glm::length(local - q) + grid_upper_distance(grid, scene_.meshes[instance.mesh], q);
    return d * instance.transform.scale;
  }
  const Aabb& world_box(uint32_t i) const { return world_box_[i]; }

 private:
  const Scene& scene_;
  const std::vector<MeshDistanceGrid>& grids_;
  std::vector<Aabb> world_box_;
  std::vector<glm::mat4> world_to_object_;
};

// Lists for a box region from its parent's candidates (a child's closest instances are among
// its parent's, so each level only re-tests the level above).
class RegionLister {
 public:
  RegionLister(const Scene& scene, const std::vector<MeshDistanceGrid>& grids, ListRule rule, float slack)
      : bounds_(scene, grids), rule_(rule), slack_(slack) {
    if (rule == ListRule::Thesis) make_influence_boxes(scene);
  }

  std::vector<uint32_t> list(const Aabb& region, const std::vector<uint32_t>& candidates) const {
    return rule_ == ListRule::Exact ? exact(region, candidates) : thesis(region, candidates);
  }

 private:
  // Exact rule (docs/design.md, "The SDF structures"): with c the centre, h the half-diagonal and D >= d(c) the scene
  // distance at c, an instance closest to some p in the region has dist(c) <= d(p) + h <=
  // d(c) + 2h <= D + 2h; so listing every instance whose lower bound at c is <= D + 2h is exact.
  std::vector<uint32_t> exact(const Aabb& region, const std::vector<uint32_t>& candidates) const {
    const glm::vec3 c = region.center();
    const float h = 0.5f * glm::length(region.extent());
    std::vector<std::pair<float, uint32_t>> by_box;
    by_box.reserve(candidates.size());
    for (uint32_t i : candidates) by_box.emplace_back(bounds_.box_lower(i, c), i);
    std::sort(by_box.begin(), by_box.end());
    float upper = std::numeric_limits<float>::infinity();
    for (const auto& [lower, i] : by_box) {  // branch and bound for D
      if (lower > upper) break;
      upper = std::min(upper, bounds_.upper(i, c));
    }
    const float limit = upper + 2.0f * h + slack_;
    std::vector<uint32_t> result;
    for (const auto& [lower, i] : by_box) {
      if (lower > limit) break;
      if (bounds_.grid_lower(i, c) <= limit) result.push_back(i);
    }
    std::sort(result.begin(), result.end());
    return result;
  }

  // Thesis 4.2: each object's "influence AABB" extends, along each of the six axis
  // directions, to the bisector with its nearest neighbour in that direction (or the scene
  // bounds); a region lists the objects whose influence box overlaps it. An approximation of
  // the Voronoi cell, neither exact nor guaranteed complete; an empty region falls back to
  // the instance whose AABB is nearest to its centre, so every leaf lists one (thesis 5.4).
  std::vector<uint32_t> thesis(const Aabb& region, const std::vector<uint32_t>& candidates) const {
    std::vector<uint32_t> result;
    for (uint32_t i : candidates) {
      const Aabb& b = influence_[i];
      if (b.min.x <= region.max.x && b.max.x >= region.min.x && b.min.y <= region.max.y && b.max.y >= region.min.y &&
          b.min.z <= region.max.z && b.max.z >= region.min.z)
        result.push_back(i);
    }
    if (result.empty() && !candidates.empty()) {
      const glm::vec3 c = region.center();
      uint32_t best = candidates[0];
      for (uint32_t i : candidates)
        if (bounds_.box_lower(i, c) < bounds_.box_lower(best, c)) best = i;
      result.push_back(best);
    }
    return result;
  }

  void make_influence_boxes(const Scene& scene) {
    const Aabb all = scene.instance_bounds();
    const size_t n = scene.instances.size();
    influence_.resize(n);
    for (size_t i = 0; i < n; ++i) {
      const glm::vec3 ci = bounds_.world_box(static_cast<uint32_t>(i)).center();
      Aabb box = bounds_.world_box(static_cast<uint32_t>(i));
      for (int axis = 0; axis < 3; ++axis) {
        for (int sign = -1; sign <= 1; sign += 2) {
          float nearest = std::numeric_limits<float>::infinity();
          float bisector = sign > 0 ? all.max[axis] : all.min[axis];
          for (size_t j = 0; j < n; ++j) {
            const glm::vec3 cj = bounds_.world_box(static_cast<uint32_t>(j)).center();
            if (j == i || (cj[axis] - ci[axis]) * static_cast<float>(sign) <= 0.0f) continue;
            const float d = glm::length(cj - ci);
            if (d < nearest) nearest = d, bisector = 0.5f * (ci[axis] + cj[axis]);
          }
          if (sign > 0) box.max[axis] = std::max(box.max[axis], bisector);
          else box.min[axis] = std::min(box.min[axis], bisector);
        }
      }
      influence_[i] = box;
    }
  }

  InstanceBounds bounds_;
  ListRule rule_;
  float slack_;  // absorbs float rounding in the bounds
  std::vector<Aabb> influence_;
};

struct CellTree {
  std::vector<OctreeNode> nodes;  // node 0 is the root; child indices local to this cell
  std::vector<uint32_t> lists;
};

Aabb octant(const Aabb& box, int k) {
  const glm::vec3 mid = box.center();
  Aabb child;
  for (int axis = 0; axis < 3; ++axis) {
    const bool upper = (k >> axis) & 1;
    child.min[axis] = upper ? mid[axis] : box.min[axis];
    child.max[axis] = upper ? box.max[axis] : mid[axis];
  }
  return child;
}

// What every cell's octree build shares: the memory the octrees hold so far, against the cap
// (a deep octree with a tiny --octree-min-size grows without end), and the progress line.
struct OctreeBudget {
  const SceneHashParams& params;
  ProgressMeter& progress;
  std::atomic<uint64_t> bytes{0};

  void spend(uint64_t more) {
    const uint64_t total = bytes.fetch_add(more, std::memory_order_relaxed) + more;
    if (total > params.max_bytes)
      throw Error("the scene hash's octrees need more than " + describe_bytes(params.max_bytes) +
                  " (--max-structure-mb " + std::to_string(params.max_bytes >> 20) + ") at --octree-depth " +
                  std::to_string(params.octree_depth) + " --octree-min-size " + six_digits(params.octree_min_size) +
                  "; lower --octree-depth, raise --octree-min-size, --octree-min-objects or --hash-cell, or raise --max-structure-mb");
    if ((total >> 24) != ((total - more) >> 24))  // every 16 MiB: a line when one cell takes long
      progress.advance(0, [&] { return describe_bytes(total) + " of octrees"; });
  }
};

void build_octree(const RegionLister& lister, OctreeBudget& budget, const Aabb& box, std::vector<uint32_t> list,
                  uint32_t depth, uint32_t node, CellTree& tree) {
  const SceneHashParams& p = budget.params;
  const float size = box.extent().x;  // cells are cubes
  const bool leaf = depth >= p.octree_depth || list.size() <= p.octree_min_objects || size <= p.octree_min_size;
  if (leaf) {
    budget.spend(list.size() * sizeof(uint32_t));
    tree.nodes[node] = {-1, static_cast<uint32_t>(tree.lists.size()), static_cast<uint32_t>(list.size()), depth};
    tree.lists.insert(tree.lists.end(), list.begin(), list.end());
    return;
  }
  budget.spend(8 * sizeof(OctreeNode));
  const uint32_t first = static_cast<uint32_t>(tree.nodes.size());
  tree.nodes[node] = {static_cast<int32_t>(first), 0, 0, depth};
  tree.nodes.resize(first + 8);
  for (int k = 0; k < 8; ++k) {
    const Aabb child = octant(box, k);
    build_octree(lister, budget, child, lister.list(child, list), depth + 1, first + k, tree);
  }
}

}  // namespace

size_t SceneHash::bytes() const {
  return cell_root.size() * sizeof(uint32_t) + nodes.size() * sizeof(OctreeNode) + instance_lists.size() * sizeof(uint32_t);
}

void validate(const SceneHashParams& p) {
  // The builder's domain, for a record made in code (one_cell_hash: a cell as large as the scene,
  // beyond --hash-cell's range; tests). The flags' ranges are their declarations' (sdf_params.cpp,
  // checked where a value is parsed), a cache file's values are checked where they are decoded
  // (cache/scene_hash_codec.cpp), and what depends on the scene is scene_hash_dims'.
  if (!(p.hash_cell > 0.0f) || !std::isfinite(p.hash_cell) || !(p.octree_min_size > 0.0f) ||
      !std::isfinite(p.octree_min_size) || p.octree_depth > 16)
    throw InternalError("a scene hash of cell " + six_digits(p.hash_cell) + ", octree depth " +
                        std::to_string(p.octree_depth) + " and min node size " + six_digits(p.octree_min_size) +
                        " (sizes must be positive and finite, the depth at most 16)");
}

namespace {

Aabb hash_bounds(const Scene& scene) {
  const Aabb bounds = scene.instance_bounds();
  return bounds.empty() ? Aabb{glm::vec3(0.0f), glm::vec3(0.0f)} : bounds;  // implicit objects only: one empty cell
}

}  // namespace

glm::uvec3 scene_hash_dims(const Scene& scene, const SceneHashParams& params) {
  validate(params);
  const glm::vec3 extent = hash_bounds(scene).extent();
  // In double: a far instance (1e29) or a tiny cell gives counts far beyond any integer type.
  const glm::dvec3 cells = glm::max(glm::ceil(glm::dvec3(extent) / static_cast<double>(params.hash_cell)), glm::dvec3(1.0));
  const double total = cells.x * cells.y * cells.z;
  if (!(total <= static_cast<double>(kMaxHashCells)))
    throw Error("--hash-cell " + six_digits(params.hash_cell) + " gives " + six_digits(cells.x) + " x " +
                six_digits(cells.y) + " x " + six_digits(cells.z) + " = " + six_digits(total) +
                " cells over the instances' bounds (" + six_digits(extent.x) + " x " + six_digits(extent.y) + " x " +
                six_digits(extent.z) + "), more than the limit of " + std::to_string(kMaxHashCells) +
                "; use a larger --hash-cell or keep the instances closer together");
  return glm::uvec3(cells);
}

SceneHash build_scene_hash(const Scene& scene, const std::vector<MeshDistanceGrid>& grids, const SceneHashParams& params) {
  const auto start = std::chrono::steady_clock::now();
  SceneHash hash;
  hash.params = params;
  hash.cell_size = params.hash_cell;
  hash.dims = scene_hash_dims(scene, params);
  const Aabb bounds = hash_bounds(scene);
  const glm::vec3 extent = bounds.extent();
  // Centre the whole-cell grid on the scene bounds.
  hash.origin = bounds.center() - 0.5f * glm::vec3(hash.dims) * params.hash_cell;

  const float slack = 1e-5f * std::max(1.0f, glm::length(extent));
  const RegionLister lister(scene, grids, params.lists, slack);
  std::vector<uint32_t> all(scene.instances.size());
  std::iota(all.begin(), all.end(), 0u);

  // Blocks of cells, top-down: candidates shrink level by level. Leaves are single cells.
  const size_t cell_count = static_cast<size_t>(hash.dims.x) * hash.dims.y * hash.dims.z;
  std::vector<CellTree> trees(cell_count);
  ProgressMeter progress("scene hash", cell_count, "cells");
  OctreeBudget budget{params, progress};
  budget.spend(cell_count * (sizeof(uint32_t) + sizeof(OctreeNode)));  // the cell table and the roots
  auto cell_box = [&](glm::uvec3 lo, glm::uvec3 hi) {
    return Aabb{hash.origin + glm::vec3(lo) * params.hash_cell, hash.origin + glm::vec3(hi) * params.hash_cell};
  };
  std::function<void(glm::uvec3, glm::uvec3, const std::vector<uint32_t>&)> build_block;
  build_block = [&](glm::uvec3 lo, glm::uvec3 hi, const std::vector<uint32_t>& parent) {
    const std::vector<uint32_t> list = lister.list(cell_box(lo, hi), parent);
    const glm::uvec3 size = hi - lo;
    if (size.x * size.y * size.z == 1) {
      CellTree& tree = trees[(static_cast<size_t>(lo.z) * hash.dims.y + lo.y) * hash.dims.x + lo.x];
      tree.nodes.resize(1);
      build_octree(lister, budget, cell_box(lo, hi), list, 0, 0, tree);
      progress.advance(1, [&] { return describe_bytes(budget.bytes.load()) + " of octrees"; });
      return;
    }
    const int axis = size.x >= size.y && size.x >= size.z ? 0 : (size.y >= size.z ? 1 : 2);
    glm::uvec3 mid_hi = hi, mid_lo = lo;
    mid_hi[axis] = lo[axis] + size[axis] / 2;
    mid_lo[axis] = mid_hi[axis];
    tbb::parallel_invoke([&] { build_block(lo, mid_hi, list); }, [&] { build_block(mid_lo, hi, list); });
  };
  build_block(glm::uvec3(0), hash.dims, all);

  // Flatten in cell order: deterministic whatever the thread schedule. Each cell's tree is freed
  // once copied, so the copy never doubles the memory.
  size_t node_total = 0, list_total = 0;
  for (const CellTree& tree : trees) node_total += tree.nodes.size(), list_total += tree.lists.size();
  hash.nodes.reserve(node_total);
  hash.instance_lists.reserve(list_total);
  hash.cell_root.resize(cell_count);
  for (size_t cell = 0; cell < cell_count; ++cell) {
    CellTree tree = std::move(trees[cell]);
    const uint32_t node_base = static_cast<uint32_t>(hash.nodes.size());
    const uint32_t list_base = static_cast<uint32_t>(hash.instance_lists.size());
    hash.cell_root[cell] = node_base;
    for (OctreeNode n : tree.nodes) {
      if (n.first_child >= 0) n.first_child += static_cast<int32_t>(node_base);
      else n.list_begin += list_base;
      hash.nodes.push_back(n);
    }
    hash.instance_lists.insert(hash.instance_lists.end(), tree.lists.begin(), tree.lists.end());
  }
  hash.build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return hash;
}

SceneHashParams one_cell_hash(const Scene& scene, uint64_t max_bytes) {
  const Aabb bounds = scene.instance_bounds();
  const glm::vec3 extent = bounds.empty() ? glm::vec3(0.0f) : bounds.extent();
  SceneHashParams p;
  p.hash_cell = std::max(1.0f, 1.001f * std::max(extent.x, std::max(extent.y, extent.z)));
  p.octree_depth = 0;
  p.lists = ListRule::Thesis;
  p.max_bytes = max_bytes;
  return p;
}

float instance_distance(const SceneSdf& sdf, const Scene& scene, uint32_t i, const glm::vec3& p, uint32_t* triangle) {
  const Instance& instance = scene.instances[i];
  const glm::vec3 local(sdf.world_to_object[i] * glm::vec4(p, 1.0f));
  return grid_distance(sdf.mesh_grids[instance.mesh], scene.meshes[instance.mesh], local, triangle) * instance.transform.scale;
}

const OctreeNode& leaf_at(const SceneHash& hash, const glm::vec3& p) {
  const glm::uvec3 cell = glm::min(glm::uvec3(glm::max((p - hash.origin) / hash.cell_size, glm::vec3(0.0f))), hash.dims - 1u);
  Aabb node_box{hash.origin + glm::vec3(cell) * hash.cell_size, hash.origin + glm::vec3(cell + 1u) * hash.cell_size};
  const OctreeNode* node = &hash.nodes[hash.cell_root[(static_cast<size_t>(cell.z) * hash.dims.y + cell.y) * hash.dims.x + cell.x]];
  while (node->first_child >= 0) {
    const glm::vec3 mid = node_box.center();
    const int k = (p.x >= mid.x ? 1 : 0) | (p.y >= mid.y ? 2 : 0) | (p.z >= mid.z ? 4 : 0);
    node_box = octant(node_box, k);
    node = &hash.nodes[static_cast<size_t>(node->first_child) + k];
  }
  return *node;
}

SceneDistance scene_distance(const SceneSdf& sdf, const Scene& scene, const glm::vec3& p) {
  const SceneHash& hash = sdf.hash;
  const Aabb box{hash.origin, hash.origin + glm::vec3(hash.dims) * hash.cell_size};
  const float outside = box_distance(box, p);
  if (outside > 0.0f) return {outside, kNone, kNone, 0};
  const OctreeNode& leaf = leaf_at(hash, p);
  SceneDistance best{std::numeric_limits<float>::infinity(), kNone, kNone, 0};
  for (uint32_t k = 0; k < leaf.list_count; ++k) {
    const uint32_t i = hash.instance_lists[leaf.list_begin + k];
    uint32_t triangle = kNone;
    const float d = instance_distance(sdf, scene, i, p, &triangle);
    ++best.evaluations;
    if (d < best.distance) best = {d, i, triangle, best.evaluations};
  }
  return best;
}

SceneDistance brute_force_scene_distance(const SceneSdf& sdf, const Scene& scene, const glm::vec3& p) {
  SceneDistance best{std::numeric_limits<float>::infinity(), kNone, kNone, 0};
  for (uint32_t i = 0; i < scene.instances.size(); ++i) {
    uint32_t triangle = kNone;
    const float d = instance_distance(sdf, scene, i, p, &triangle);
    ++best.evaluations;
    if (d < best.distance) best = {d, i, triangle, best.evaluations};
  }
  return best;
}

}  // namespace sdfbench::sdf
