#include "renderers/sdf_global/cell_triangle_refs.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <unordered_map>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include "renderers/sdf_global/triangle_box_overlap.h"
#include "util/error.h"
#include "util/input_file.h"
#include "util/progress.h"

namespace sdfbench::sdf {
namespace {

std::string too_large(const std::string& what, uint64_t bytes) {
  return "sdf-global: the exact hits' triangle references (" + what + ") would need " + describe_bytes(bytes) +
         ", more than --max-structure-mb allows; use a smaller --list-split, a larger --global-voxel or "
         "--exact-lists instances";
}

// The sets, shared: a set's words are looked up by their hash before one is appended.
class SetStore {
 public:
  explicit SetStore(std::vector<uint32_t>& words) : words_(words) { words_.assign(1, 0u); }  // offset 0: the empty set
  uint32_t add(const std::vector<uint32_t>& set) {
    size_t h = set.size();
    for (uint32_t w : set) h = h * 1000003u ^ w;
    auto& offsets = by_hash_[h];
    for (uint32_t offset : offsets)
      if (words_[offset] == set.size() && std::equal(set.begin(), set.end(), words_.begin() + offset + 1)) return offset;
    const uint32_t offset = static_cast<uint32_t>(words_.size());
    words_.push_back(static_cast<uint32_t>(set.size()));
    words_.insert(words_.end(), set.begin(), set.end());
    offsets.push_back(offset);
    return offset;
  }

 private:
  std::vector<uint32_t>& words_;
  std::unordered_map<size_t, std::vector<uint32_t>> by_hash_;
};

}  // namespace

CellTriangleRefs build_cell_triangle_refs(const Scene& scene, const BrickField& field, uint32_t split, uint64_t max_bytes) {
  const auto start = std::chrono::steady_clock::now();
  if (split < 1 || split > kMaxListSplit)
    throw Error("--list-split " + std::to_string(split) + ": must be between 1 and " + std::to_string(kMaxListSplit));
  CellTriangleRefs refs;
  refs.split = split;
  refs.cells_per_side = kBrickCells * split;
  const uint64_t cells_per_brick = uint64_t(refs.cells_per_side) * refs.cells_per_side * refs.cells_per_side;
  const size_t stored = field.stored_bricks();
  refs.brick_tables.assign(stored, kNoCellTable);
  refs.sets.assign(1, 0u);
  if (stored == 0 || scene.instances.empty()) return refs;
  if (uint64_t(stored) * cells_per_brick >= (uint64_t(1) << 32))
    throw Error(too_large("cell keys beyond 32 bits", uint64_t(stored) * cells_per_brick * 4));

  // Global triangle indices (as the kernels' vertex tables) and each instance's first reference id.
  std::vector<uint32_t> mesh_first(scene.meshes.size() + 1, 0);
  for (size_t m = 0; m < scene.meshes.size(); ++m)
    mesh_first[m + 1] = mesh_first[m] + static_cast<uint32_t>(scene.meshes[m].triangles.size());
  if (mesh_first.back() >= kInstanceWord) throw Error("sdf-global: too many triangles for the references' 31-bit indices");
  std::vector<uint64_t> instance_first(scene.instances.size() + 1, 0);
  for (size_t i = 0; i < scene.instances.size(); ++i)
    instance_first[i + 1] = instance_first[i] + scene.meshes[scene.instances[i].mesh].triangles.size();
  if (instance_first.back() >= (uint64_t(1) << 32))
    throw Error("sdf-global: more than 2^32 instanced triangles for the references; use --exact-lists instances");

  const float cell = field.voxel / float(split);
  const glm::uvec3 lattice_cells = field.bricks * refs.cells_per_side;
  const float coordinate_slack =
      4e-5f * std::max({glm::length(field.origin), glm::length(field.box_max()), 1e-30f});
  const glm::vec3 half(0.5f * cell + kRefSlackVoxels * field.voxel + coordinate_slack);

  // (cell key << 32 | reference id) per crossing, gathered per thread, bounded as they grow.
  tbb::enumerable_thread_specific<std::vector<uint64_t>> gathered;
  std::atomic<uint64_t> total{0};
  ProgressMeter progress("triangle references", scene.instances.size(), "instances");
  tbb::parallel_for(tbb::blocked_range<size_t>(0, scene.instances.size()), [&](const tbb::blocked_range<size_t>& r) {
    std::vector<uint64_t>& out = gathered.local();
    const size_t before = out.size();
    for (size_t i = r.begin(); i != r.end(); ++i) {
      const Instance& instance = scene.instances[i];
      const Mesh& mesh = scene.meshes[instance.mesh];
      const glm::mat4 to_world = instance.transform.object_to_world();
      for (size_t t = 0; t < mesh.triangles.size(); ++t) {
        glm::vec3 v[3];
        for (int k = 0; k < 3; ++k) v[k] = glm::vec3(to_world * glm::vec4(mesh.positions[mesh.triangles[t][k]], 1.0f));
        const glm::vec3 lo = glm::min(v[0], glm::min(v[1], v[2])) - half + 0.5f * cell;
        const glm::vec3 hi = glm::max(v[0], glm::max(v[1], v[2])) + half - 0.5f * cell;
        const glm::vec3 a = glm::floor((lo - field.origin) / cell), b = glm::floor((hi - field.origin) / cell);
        const glm::uvec3 c0(glm::clamp(a, glm::vec3(0.0f), glm::vec3(lattice_cells - 1u)));
        const glm::uvec3 c1(glm::clamp(b, glm::vec3(0.0f), glm::vec3(lattice_cells - 1u)));
        const uint64_t id = instance_first[i] + t;
        // Brick by brick first: a large triangle's box spans many bricks that are empty or that
        // it does not cross.
        const glm::uvec3 b0 = c0 / refs.cells_per_side, b1 = c1 / refs.cells_per_side;
        for (uint32_t bz = b0.z; bz <= b1.z; ++bz)
          for (uint32_t by = b0.y; by <= b1.y; ++by)
            for (uint32_t bx = b0.x; bx <= b1.x; ++bx) {
              const glm::uvec3 brick(bx, by, bz);
              const uint32_t slot = field.indirection[bx + size_t(field.bricks.x) * (by + size_t(field.bricks.y) * bz)];
              if (slot == kEmptyBrick) continue;  // an empty brick holds no surface
              const glm::vec3 brick_half = 0.5f * cell * float(refs.cells_per_side) + (half - 0.5f * cell);
              if (!triangle_meets_box(v[0], v[1], v[2], field.origin + cell * float(refs.cells_per_side) * (glm::vec3(brick) + 0.5f),
                                      brick_half))
                continue;
              const glm::uvec3 lo_cell = glm::max(c0, brick * refs.cells_per_side);
              const glm::uvec3 hi_cell = glm::min(c1, brick * refs.cells_per_side + refs.cells_per_side - 1u);
              for (uint32_t z = lo_cell.z; z <= hi_cell.z; ++z)
                for (uint32_t y = lo_cell.y; y <= hi_cell.y; ++y)
                  for (uint32_t x = lo_cell.x; x <= hi_cell.x; ++x) {
                    const glm::uvec3 g(x, y, z), local = g - brick * refs.cells_per_side;
                    const glm::vec3 centre = field.origin + cell * (glm::vec3(g) + 0.5f);
                    if (!triangle_meets_box(v[0], v[1], v[2], centre, half)) continue;
                    const uint64_t key = slot * cells_per_brick + local.x +
                                         refs.cells_per_side * (local.y + uint64_t(refs.cells_per_side) * local.z);
                    out.push_back(key << 32 | id);
                  }
            }
      }
    }
    if ((total += out.size() - before) * sizeof(uint64_t) > max_bytes)
      throw Error(too_large("while gathering them", total.load() * sizeof(uint64_t)));
    progress.advance(r.size());
  });
  std::vector<uint64_t> keys;
  keys.reserve(total.load());
  for (std::vector<uint64_t>& part : gathered) {
    keys.insert(keys.end(), part.begin(), part.end());
    std::vector<uint64_t>().swap(part);
  }
  tbb::parallel_sort(keys.begin(), keys.end());
  refs.references = keys.size();

  // Cell tables for the bricks some triangle crosses, then each cell's set.
  uint64_t table_words = 0;
  for (size_t k = 0; k < keys.size(); ++k) {
    const uint64_t slot = (keys[k] >> 32) / cells_per_brick;
    if (refs.brick_tables[slot] == kNoCellTable) {
      refs.brick_tables[slot] = static_cast<uint32_t>(std::min<uint64_t>(table_words, kNoCellTable - 1));
      table_words += cells_per_brick;
    }
  }
  if ((table_words + refs.brick_tables.size()) * sizeof(uint32_t) > max_bytes || table_words >= kNoCellTable)
    throw Error(too_large("cell tables", (table_words + refs.brick_tables.size()) * sizeof(uint32_t)));
  refs.cells.assign(table_words, 0u);
  SetStore store(refs.sets);
  std::vector<uint32_t> set;
  for (size_t k = 0; k < keys.size();) {
    const uint64_t key = keys[k] >> 32;
    set.clear();
    uint32_t current = kInstanceWord;
    for (; k < keys.size() && (keys[k] >> 32) == key; ++k) {
      const uint64_t id = keys[k] & 0xffffffffu;
      const uint32_t i = static_cast<uint32_t>(std::upper_bound(instance_first.begin(), instance_first.end(), id) -
                                               instance_first.begin() - 1);
      if (i != current) set.push_back(kInstanceWord | i), current = i;
      set.push_back(mesh_first[scene.instances[i].mesh] + static_cast<uint32_t>(id - instance_first[i]));
    }
    const uint64_t slot = key / cells_per_brick;
    refs.cells[refs.brick_tables[slot] + (key - slot * cells_per_brick)] = store.add(set);
    if (refs.sets.size() * sizeof(uint32_t) > max_bytes) throw Error(too_large("sets", refs.sets.size() * sizeof(uint32_t)));
  }
  if (refs.sets.size() >= kInstanceWord) throw Error(too_large("sets beyond 31-bit offsets", refs.sets.size() * 4));
  refs.build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return refs;
}

}  // namespace sdfbench::sdf
