#include "renderers/sdf/build_reuse.h"

#include <any>
#include <bit>
#include <cstring>
#include <list>
#include <optional>
#include <mutex>
#include <span>
#include <string>
#include <utility>

#include "renderers/sdf/build_store.h"
#include "renderers/sdf/sdf_cache.h"
#include "util/fnv1a.h"

namespace sdfbench::sdf {
namespace {

// Keys are the exact bytes of what a build depends on: digests of the geometry, raw parameter
// values (floats by their bits, so 0.5 and 0.50000001 are two builds).
class Key {
 public:
  explicit Key(const char* kind) : text_(kind) {}
  template <typename T>
  Key& add(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    text_.append(reinterpret_cast<const char*>(&value), sizeof value);
    return *this;
  }
  Key& add(const MeshGridParams& p) {
    return add(p.cell_size).add(p.cells_per_extent).add(p.margin_cells).add(p.rule).add(p.subdivision).add(p.max_bytes)
        .add(p.scale_with_triangles);
  }
  Key& add(const SceneHashParams& p) {
    return add(p.hash_cell).add(p.octree_depth).add(p.octree_min_objects).add(p.octree_min_size).add(p.lists).add(p.max_bytes);
  }
  const std::string& text() const { return text_; }

 private:
  std::string text_;
};

uint64_t mesh_digest(const Mesh& mesh) {
  uint64_t h = fnv1a64(std::as_bytes(std::span(mesh.positions)));
  return fnv1a64(std::as_bytes(std::span(mesh.triangles)), h);
}

struct Entry {
  std::string key;
  std::any value;
  uint64_t bytes = 0;
};

std::mutex mutex;
std::list<Entry> entries;  // most recently used first
uint64_t kept_bytes = 0;

template <typename T>
T reuse(const Key& key, const std::function<T()>& build) {
  {
    const std::lock_guard lock(mutex);
    for (auto it = entries.begin(); it != entries.end(); ++it) {
      if (it->key != key.text()) continue;
      entries.splice(entries.begin(), entries, it);
      return std::any_cast<const T&>(entries.front().value);
    }
  }
  T built = build();  // outside the lock: builds run in parallel inside (TBB)
  const uint64_t bytes = built.bytes();
  if (bytes > kMaxReusedBytes) return built;
  const std::lock_guard lock(mutex);
  entries.push_front(Entry{key.text(), built, bytes});
  kept_bytes += bytes;
  while (kept_bytes > kMaxReusedBytes) {
    kept_bytes -= entries.back().bytes;
    entries.pop_back();
  }
  return built;
}

}  // namespace

MeshDistanceGrid reuse_mesh_grid(const Mesh& mesh, const MeshGridParams& params,
                                 const std::function<MeshDistanceGrid()>& build) {
  const Key key = Key("mesh grid").add(mesh_digest(mesh)).add(params);
  return reuse<MeshDistanceGrid>(key, [&] {
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
  return reuse(Key("scene hash").add(scene_geometry_hash(scene)).add(grid).add(params), build);
}

BrickField reuse_brick_field(const Mesh& mesh, const MeshGridParams& grid, const BrickFieldParams& params,
                             const std::function<BrickField()>& build) {
  return reuse(Key("brick field").add(mesh_digest(mesh)).add(grid).add(params.voxels).add(params.band).add(params.format)
                   .add(params.max_bytes),
               build);
}

GlobalField reuse_global_field(const Scene& scene, const MeshGridParams& grid, const GlobalFieldParams& params,
                               const std::function<GlobalField()>& build) {
  return reuse(Key("global field").add(scene_geometry_hash(scene)).add(grid).add(params.voxel).add(params.band)
                   .add(params.format).add(params.max_bytes),
               build);
}

void forget_reused_builds() {
  const std::lock_guard lock(mutex);
  entries.clear();
  kept_bytes = 0;
}

}  // namespace sdfbench::sdf
