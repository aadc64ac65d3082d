#pragma once
// Mesh grids kept on disk between processes: with $SDFBENCH_BUILD_STORE naming a folder, a grid
// one process built is loaded by the next that asks for the same mesh and parameters, so a test
// suite (ctest runs each test in a process of its own) or a sweep split over processes builds
// each grid once. An entry serves only the executable that wrote it (its build ID names the
// entry's folder): an edited builder never reads an older build. Entries are SDF cache files
// (sdf_cache.h) of the mesh alone, read back with all of the cache's checks. A folder that
// cannot be written, or an entry that does not load, costs a build and nothing else, silently:
// the grid is the same either way. Unset: nothing is read or written.
#include <cstdint>
#include <optional>

#include "renderers/sdf/mesh_distance_grid.h"
#include "scenes/mesh.h"

namespace sdfbench::sdf {

// `key` identifies the mesh and parameters (build_reuse.cpp's digest of both).
std::optional<MeshDistanceGrid> load_stored_mesh_grid(const Mesh& mesh, const MeshGridParams& params, uint64_t key);
void store_mesh_grid(const Mesh& mesh, const MeshGridParams& params, uint64_t key, const MeshDistanceGrid& grid);

}  // namespace sdfbench::sdf
