#include "renderers/sdf/build_reuse.h"

#include <list>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <utility>

#include "renderers/sdf/build_store.h"
#include "renderers/sdf/sdf_cache.h"
#include "util/fnv1a.h"

namespace sdfbench::sdf {

BuildKey& BuildKey::add(const MeshGridParams& p) {
  return add(p.cell_size).add(p.cells_per_extent).add(p.margin_cells).add(p.rule).add(p.subdivision).add(p.max_bytes)
      .add(p.scale_with_triangles);
}

BuildKey& BuildKey::add(const SceneHashParams& p) {
  return add(p.hash_cell).add(p.octree_depth).add(p.octree_min_objects).add(p.octree_min_size).add(p.lists).add(p.max_bytes);
}

BuildKey& BuildKey::add(const Mesh& mesh) {
  const uint64_t h = fnv1a64(std::as_bytes(std::span(mesh.positions)));
  return add(fnv1a64(std::as_bytes(std::span(mesh.triangles)), h));
}

BuildKey& BuildKey::add(const Scene& scene) { return add(scene_geometry_hash(scene)); }

namespace {

struct Entry {
  std::string key;
  std::shared_ptr<const void> value;
  uint64_t bytes = 0;
};

std::mutex mutex;
std::list<Entry> entries;  // most recently used first
uint64_t kept_bytes = 0;

}  // namespace

std::shared_ptr<const void> detail::reuse_build(
    const std::string& key, const std::function<std::pair<std::shared_ptr<const void>, uint64_t>()>& build) {
  {
    const std::lock_guard lock(mutex);
    for (auto it = entries.begin(); it != entries.end(); ++it) {
      if (it->key != key) continue;
      entries.splice(entries.begin(), entries, it);
      return entries.front().value;
    }
  }
  auto [built, bytes] = build();  // outside the lock: builds run in parallel inside (TBB)
  if (bytes > kMaxReusedBytes) return built;
  const std::lock_guard lock(mutex);
  entries.push_front(Entry{key, built, bytes});
  kept_bytes += bytes;
  while (kept_bytes > kMaxReusedBytes) {
    kept_bytes -= entries.back().bytes;
    entries.pop_back();
  }
  return built;
}

MeshDistanceGrid reuse_mesh_grid(const Mesh& mesh, const MeshGridParams& params,
                                 const std::function<MeshDistanceGrid()>& build) {
  const BuildKey key = BuildKey("mesh grid").add(mesh).add(params);
  return *reuse_build(key, [&] {
    // Then another process' build of the same executable (build_store.h), then a build.
    const uint64_t id = fnv1a64(key.text());
    if (std::optional<MeshDistanceGrid> stored = load_stored_mesh_grid(mesh, params, id)) return std::move(*stored);
    MeshDistanceGrid grid = build();
    store_mesh_grid(mesh, params, id, grid);
    return grid;
  });
}

SceneHash reuse_scene_hash(const Scene& scene, const MeshGridParams& grid, const SceneHashParams& params,
                           const std::function<SceneHash()>& build) {
  return *reuse_build(BuildKey("scene hash").add(scene).add(grid).add(params), build);
}

void forget_reused_builds() {
  const std::lock_guard lock(mutex);
  entries.clear();
  kept_bytes = 0;
}

}  // namespace sdfbench::sdf
