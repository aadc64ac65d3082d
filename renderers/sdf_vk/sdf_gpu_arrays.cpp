#include "renderers/sdf_vk/sdf_gpu_arrays.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include "renderers/frame_params.h"
#include "renderers/sdf/traced_distance.h"
#include "util/error.h"

namespace sdfbench {
namespace {

uint32_t bits(float f) { return std::bit_cast<uint32_t>(f); }

glm::uvec4 bits(const glm::vec3& v, uint32_t w) { return glm::uvec4(bits(v.x), bits(v.y), bits(v.z), w); }

// Row r of an affine matrix (glm is column-major) as float bits.
glm::uvec4 row_bits(const glm::mat4& m, int r) { return glm::uvec4(bits(m[0][r]), bits(m[1][r]), bits(m[2][r]), bits(m[3][r])); }

void check_word(size_t value, const char* what) {
  if (value >= SDF_LEAF_BIT)
    throw Error(std::string("the scene hash has too many ") + what + " for the GPU's 31-bit node words (" +
                std::to_string(value) + "); use a larger --hash-cell or --octree-min-objects");
}

// Distance between two boxes (0 when they touch or overlap).
float box_box_distance(const glm::vec3& lo_a, const glm::vec3& hi_a, const Aabb& b) {
  const glm::vec3 gap = glm::max(glm::max(lo_a - b.max, b.min - hi_a), glm::vec3(0.0f));
  return glm::length(gap);
}

// Re-encodes the CPU's flat octrees as node words: a cell's root goes into the hash-cell
// table (one fetch fewer per step), its descendants into the node table, 8 siblings together.
// `instance_boxes` (--cell-bound, else null): each leaf's bound, the least distance from its box to
// a listed instance's box. The traced distance at any point of the leaf is the least over the listed
// instances, each at least its box's distance (triangles and grid bounds lie inside the box).
// `overlap_boxes` (sdf-bricks, else null): each leaf's list in the same set, those instances whose
// box meets the leaf's box first, their count in the list's second word (instead of a bound): a
// ray's segment inside the leaf can only hit those.
void flatten_hash(const sdf::SceneHash& hash, const std::vector<Aabb>* instance_boxes, const std::vector<Aabb>* overlap_boxes,
                  SdfGpuArrays& out) {
  // Neighbouring leaves often list the same instances: a leaf equal to the previous one shares
  // its list (thesis:bunny:1000, octree: 69 -> 25 MB of lists).
  size_t previous = 0;
  // Rounding: the kernel's descent computes the leaf boxes in floats too.
  const float slack = 1e-5f * hash.cell_size;
  std::function<uint32_t(uint32_t, glm::vec3, float)> encode = [&](uint32_t index, glm::vec3 lo, float size) -> uint32_t {
    const sdf::OctreeNode& node = hash.nodes[index];
    if (node.first_child < 0) {
      std::vector<uint32_t> ordered(hash.instance_lists.begin() + node.list_begin,
                                    hash.instance_lists.begin() + node.list_begin + node.list_count);
      const auto list = ordered.begin();
      uint32_t second_word = 0;
      if (overlap_boxes) {
        const glm::vec3 hi = lo + size;
        const auto overlapping = std::stable_partition(ordered.begin(), ordered.end(), [&](uint32_t i) {
          const Aabb& b = (*overlap_boxes)[i];
          return glm::all(glm::lessThanEqual(b.min, hi + slack)) && glm::all(glm::lessThanEqual(lo - slack, b.max));
        });
        second_word = static_cast<uint32_t>(overlapping - ordered.begin());
      }
      float bound = 0.0f;
      if (instance_boxes && node.list_count > 0) {
        bound = std::numeric_limits<float>::max();
        for (auto it = list; it != list + node.list_count; ++it)
          bound = std::min(bound, box_box_distance(lo, lo + size, (*instance_boxes)[*it]));
        bound = std::max(bound - slack, 0.0f);
        second_word = bits(bound);
      }
      const bool same = !out.instance_lists.empty() && out.instance_lists[previous] == node.list_count &&
                        out.instance_lists[previous + 1] == second_word &&
                        std::equal(list, list + node.list_count, out.instance_lists.begin() + previous + 2);
      if (!same) {
        previous = out.instance_lists.size();
        check_word(previous, "instance-list entries");
        out.instance_lists.push_back(node.list_count);
        out.instance_lists.push_back(second_word);
        out.instance_lists.insert(out.instance_lists.end(), list, list + node.list_count);
      }
      return SDF_LEAF_BIT | static_cast<uint32_t>(previous);
    }
    const size_t first = out.octree_nodes.size();
    check_word(first + 8, "octree nodes");
    out.octree_nodes.resize(first + 8);
    const float half = 0.5f * size;
    for (uint32_t k = 0; k < 8; ++k) {
      const glm::vec3 child_lo = lo + half * glm::vec3(k & 1u, (k >> 1) & 1u, (k >> 2) & 1u);
      const uint32_t word = encode(static_cast<uint32_t>(node.first_child) + k, child_lo, half);
      out.octree_nodes[first + k] = word;
    }
    // Eight leaves sharing one list are that leaf: the same distances, one descent step less.
    const uint32_t word = out.octree_nodes[first];
    if ((word & SDF_LEAF_BIT) && std::all_of(out.octree_nodes.begin() + first, out.octree_nodes.begin() + first + 8,
                                             [word](uint32_t w) { return w == word; })) {
      out.octree_nodes.resize(first);
      return word;
    }
    return static_cast<uint32_t>(first);
  };
  out.hash_cells.reserve(hash.cell_root.size());
  for (size_t c = 0; c < hash.cell_root.size(); ++c) {
    const glm::uvec3 cell(c % hash.dims.x, (c / hash.dims.x) % hash.dims.y, c / (size_t(hash.dims.x) * hash.dims.y));
    out.hash_cells.push_back(encode(hash.cell_root[c], hash.origin + glm::vec3(cell) * hash.cell_size, hash.cell_size));
  }
}

}  // namespace

SdfGpuArrays flatten_for_gpu(const Scene& scene, const sdf::SceneSdf& sdf, const sdf::SphereTraceParams& tracing,
                             LeafLists leaf_lists) {
  SdfGpuArrays out;
  const sdf::SceneHash& hash = sdf.hash;
  out.params.hash_origin = glm::vec4(hash.origin, hash.cell_size);
  out.params.hash_dims = glm::uvec4(hash.dims, tracing.max_steps);
  out.params.tracing =
      glm::vec4(tracing.hit_epsilon * scene_scale(scene), tracing.hit == sdf::HitMode::exact ? 1.0f : 0.0f,
                tracing.footprint, 0.0f);
  out.params.options = glm::vec4(tracing.over_relax, 0.0f, 0.0f, 0.0f);
  const sdf::TraceCulling culling = sdf::make_trace_culling(scene, sdf);
  if (tracing.cell_bound && leaf_lists == LeafLists::overlapping_first)
    throw InternalError("--cell-bound and overlap-first lists share a word");
  flatten_hash(hash, tracing.cell_bound ? &culling.instance_boxes : nullptr,
               leaf_lists == LeafLists::overlapping_first ? &culling.instance_boxes : nullptr, out);

  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    const sdf::MeshDistanceGrid& grid = sdf.mesh_grids[m];
    const uint32_t first_triangle = static_cast<uint32_t>(out.vertices.size() / 3);
    const uint32_t first_cell = static_cast<uint32_t>(out.grid_cells.size());
    const uint32_t list_base = static_cast<uint32_t>(out.grid_entries.size() / SDF_ENTRY_TEXELS);
    out.mesh_records.push_back(bits(grid.origin, bits(grid.cell_size)));
    out.mesh_records.push_back(glm::uvec4(grid.dims, first_cell));
    out.mesh_records.push_back(bits(mesh.bounds.min, first_triangle));
    out.mesh_records.push_back(bits(mesh.bounds.max, 0u));
    for (size_t c = 0; c < grid.cell_count(); ++c) {
      if (grid.is_far(c)) {
        const uint32_t far = std::bit_cast<uint32_t>(std::abs(grid.far_distance[c])) | SDF_FAR_CELL;
        out.grid_cells.emplace_back(far, far);
      } else {
        out.grid_cells.emplace_back(list_base + grid.cell_begin[c], list_base + grid.cell_begin[c + 1]);
      }
    }
    // The exact hits' lists (crossing_lists.h), their indices made global.
    const sdf::MeshCrossingLists& crossings = culling.crossings[m];
    const uint64_t crossing_base = out.crossing_triangles.size();
    if (crossing_base + crossings.triangles.size() >= std::numeric_limits<uint32_t>::max())
      throw Error("the mesh grids' exact-hit lists have too many entries for the kernels' 32-bit indices; use a larger "
                  "--mesh-cell or fewer --cells-per-extent");
    for (size_t c = 0; c < grid.cell_count(); ++c)
      out.crossing_cells.emplace_back(uint32_t(crossing_base + crossings.cell_begin[c]),
                                      uint32_t(crossing_base + crossings.cell_begin[c + 1]));
    for (uint32_t k : crossings.triangles) out.crossing_triangles.push_back(first_triangle + k);
    const sdf::MeshTraceLists& lists = culling.meshes[m];
    for (size_t i = 0; i < lists.triangles.size(); ++i) {
      const glm::uvec3& t = mesh.triangles[lists.triangles[i]];
      out.grid_entries.emplace_back(mesh.positions[t[0]], lists.centre_distances[i]);
      out.grid_entries.emplace_back(mesh.positions[t[1]], std::bit_cast<float>(first_triangle + lists.triangles[i]));
      out.grid_entries.emplace_back(mesh.positions[t[2]], 0.0f);
    }
    for (const glm::uvec3& t : mesh.triangles) {
      for (int k = 0; k < 3; ++k) {
        out.vertices.emplace_back(mesh.positions[t[k]], 1.0f);
        out.normals.emplace_back(mesh.normals[t[k]], 0.0f);
      }
    }
  }

  for (size_t i = 0; i < scene.instances.size(); ++i) {
    const Instance& instance = scene.instances[i];
    const glm::mat4 object_to_world = instance.transform.object_to_world();
    const Aabb& box = culling.instance_boxes[i];
    out.instance_records.push_back(bits(box.min, instance.mesh));
    out.instance_records.push_back(bits(box.max, bits(instance.transform.scale)));
    for (int r = 0; r < 3; ++r) out.instance_records.push_back(row_bits(sdf.world_to_object[i], r));
    for (int r = 0; r < 3; ++r) out.instance_records.push_back(row_bits(object_to_world, r));
    out.instance_records[out.instance_records.size() - 3].w = instance.material;
  }
  static_assert(SDF_INSTANCE_TEXELS == 8 && SDF_MESH_TEXELS == 4 && SDF_ENTRY_TEXELS == 3,
                "records above match the layout");
  return out;
}

}  // namespace sdfbench
