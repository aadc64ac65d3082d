#pragma once
// This process' earlier builds, reused: a table or a test draws one scene with several SDF
// backends (sdf-hash, sdf-octree, sdf-bricks, sdf-global, sdf-cpu) and object counts, and each
// built the same mesh grids, scene hash and optional structures (brick fields, global field)
// again. A build is reused only for the same key: the same geometry and the same parameters
// (max_bytes included), so the result is the one a fresh build gives, bit for bit; its build_ms
// stays the time it took when built, as with the on-disk cache (sdf_cache.h). Bounded: the
// oldest entries go once the kept structures pass kMaxReusedBytes. Thread-safe. Mesh grids, the
// most common build, also have a tier on disk that later processes of the same executable read,
// when $SDFBENCH_BUILD_STORE names a folder (build_store.h).
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "renderers/sdf/mesh_distance_grid.h"
#include "renderers/sdf/scene_hash.h"
#include "scenes/scene.h"

namespace sdfbench::sdf {

inline constexpr uint64_t kMaxReusedBytes = uint64_t(1) << 30;

// What a build depends on, as bytes: its kind ("brick field"), digests of the geometry, raw
// parameter values (floats by their bits, so 0.5 and 0.50000001 are two builds).
class BuildKey {
 public:
  explicit BuildKey(const char* kind) : text_(kind) {}
  template <typename T>
  BuildKey& add(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    text_.append(reinterpret_cast<const char*>(&value), sizeof value);
    return *this;
  }
  BuildKey& add(const MeshGridParams& params);   // every field, max_bytes included
  BuildKey& add(const SceneHashParams& params);  // every field, max_bytes included
  BuildKey& add(const Mesh& mesh);    // a digest of its positions and triangles
  BuildKey& add(const Scene& scene);  // a digest of its geometry (scene_geometry_hash)
  const std::string& text() const { return text_; }

 private:
  std::string text_;
};

namespace detail {
// The structure kept under `key`, or `build()`'s (kept unless it holds more than kMaxReusedBytes).
std::shared_ptr<const void> reuse_build(const std::string& key,
                                        const std::function<std::pair<std::shared_ptr<const void>, uint64_t>()>& build);
}  // namespace detail

// An earlier build with this key (shared, never copied), or `build()`'s result, whose type has
// bytes(): any structure's builder reuses its builds through this.
template <class Build>
std::shared_ptr<const std::invoke_result_t<Build&>> reuse_build(const BuildKey& key, Build&& build) {
  using T = std::invoke_result_t<Build&>;
  return std::static_pointer_cast<const T>(detail::reuse_build(key.text(), [&]() -> std::pair<std::shared_ptr<const void>, uint64_t> {
    auto built = std::make_shared<const T>(build());
    const uint64_t bytes = built->bytes();
    return {std::move(built), bytes};
  }));
}

// The mesh's grid with these parameters: an earlier build of the same mesh, or `build()`.
MeshDistanceGrid reuse_mesh_grid(const Mesh& mesh, const MeshGridParams& params,
                                 const std::function<MeshDistanceGrid()>& build);

// The scene's hash and octrees over its instances, whose lists the mesh grids bound (keyed by the
// scene's geometry, the grid parameters and the hash's): sdf-octree and sdf-bricks share one.
SceneHash reuse_scene_hash(const Scene& scene, const MeshGridParams& grid, const SceneHashParams& params,
                           const std::function<SceneHash()>& build);

// Forgets every kept build (tests that time or count builds).
void forget_reused_builds();

}  // namespace sdfbench::sdf
