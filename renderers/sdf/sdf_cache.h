#pragma once
// The on-disk cache of a scene's SDF structures (mesh distance grids + scene hash/octrees, and
// the optional structures when built: sdf-bricks' brick fields, sdf-global's global field), so
// that renders and benchmarks reuse a build. The file format and its validation live in
// sdf_cache_format.h; this file ties a cache to a scene: its content hash, the build parameters,
// and the policy for a cache that does not match.
#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <string>

#include "renderers/sdf/scene_hash.h"
#include "renderers/structure_cache_options.h"
#include "scenes/scene.h"

namespace sdfbench::sdf {

// What a scene's structures depend on: every mesh's positions and triangles, and every
// instance's mesh and transform (plus the builder version). Materials, lights, camera, sky and
// floor do not change the structures, so they do not invalidate a cache.
uint64_t scene_geometry_hash(const Scene& scene);

// Writes atomically (temporary file + rename): a reader never sees a half-written cache. A cache
// over kMaxSdfCacheBytes (which no loader would read) is refused instead (Error). A file that
// cannot be written (read-only file system) is an Error, or with `warn_if_unwritable` (a render's
// cache: the render goes on) a warning on stderr and false.
bool write_sdf_cache(const std::filesystem::path& path, const Scene& scene, const SceneSdf& sdf,
                     const MeshGridParams& mesh_params, bool warn_if_unwritable = false);

// Reads and validates a cache completely, then checks it belongs to this scene and these
// parameters. Throws Error with a clear message for a missing, special (FIFO, device,
// directory), oversized, truncated, corrupt, hostile or stale file; never returns structures
// that were not validated.
// `extras`: the optional structures the cache must also hold, built with the requests'
// parameters (structure_request.h: brick fields for sdf-bricks, the global field for
// sdf-global); a cache with more serves the backends that need fewer.
SceneSdf load_sdf_cache(const std::filesystem::path& path, const Scene& scene, const MeshGridParams& mesh_params,
                        const SceneHashParams& hash_params, const StructureRequests& extras = {});

// The cache settings every backend receives (renderers/structure_cache_options.h).
using sdfbench::BadCachePolicy;
using sdfbench::CacheOptions;

// The one entry point for backends: no path -> build; a missing file -> build and write it; a
// valid matching file -> load it (skipping the build); an invalid or stale file -> the policy;
// something that cannot be a cache (not a regular file, or over the size limit) -> an error.
// A valid cache without one of `extras` gets it added (and is written back); one holding it with
// other parameters (or in another codec version) is stale. Says on `log` which of these happened.
SceneSdf obtain_scene_sdf(const Scene& scene, const MeshGridParams& mesh_params, const SceneHashParams& hash_params,
                          const CacheOptions& cache, std::ostream& log, const StructureRequests& extras = {});

}  // namespace sdfbench::sdf
