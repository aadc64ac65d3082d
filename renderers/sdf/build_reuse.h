#pragma once
// This process' earlier builds, reused: a table or a test draws one scene with several SDF
// backends (sdf-hash, sdf-octree, sdf-bricks, sdf-global, sdf-cpu) and object counts, and each
// built the same mesh grids, scene hash, brick fields and global field again. A build is reused
// only for the same geometry and the same parameters (max_bytes included), so the result is the
// one a fresh build gives, bit for bit; its build_ms stays the time it took when built, as with
// the on-disk cache (sdf_cache.h). Bounded: the oldest entries go once the kept structures pass
// kMaxReusedBytes. Thread-safe. Mesh grids, the most common build, also have a tier on disk that
// later processes of the same executable read, when $SDFBENCH_BUILD_STORE names a folder
// (build_store.h).
#include <cstdint>
#include <functional>
#include <vector>

#include "renderers/sdf_bricks/brick_field.h"
#include "renderers/sdf_global/global_field.h"
#include "renderers/sdf/mesh_distance_grid.h"
#include "renderers/sdf/scene_hash.h"
#include "scenes/scene.h"

namespace sdfbench::sdf {

inline constexpr uint64_t kMaxReusedBytes = uint64_t(1) << 30;

// The mesh's grid with these parameters: an earlier build of the same mesh, or `build()`.
MeshDistanceGrid reuse_mesh_grid(const Mesh& mesh, const MeshGridParams& params,
                                 const std::function<MeshDistanceGrid()>& build);

// The scene's hash and octrees over its instances, whose lists the mesh grids bound (keyed by the
// scene's geometry, the grid parameters and the hash's): sdf-octree and sdf-bricks share one.
SceneHash reuse_scene_hash(const Scene& scene, const MeshGridParams& grid, const SceneHashParams& params,
                           const std::function<SceneHash()>& build);

// The mesh's brick field sampled from its grid with these parameters (keyed by the mesh, the grid
// parameters and the field's).
BrickField reuse_brick_field(const Mesh& mesh, const MeshGridParams& grid, const BrickFieldParams& params,
                             const std::function<BrickField()>& build);

// The scene's global field (keyed by the scene's geometry, the grid parameters and the field's).
GlobalField reuse_global_field(const Scene& scene, const MeshGridParams& grid, const GlobalFieldParams& params,
                               const std::function<GlobalField()>& build);

// Forgets every kept build (tests that time or count builds).
void forget_reused_builds();

}  // namespace sdfbench::sdf
