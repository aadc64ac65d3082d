#include "renderers/sdf/build_store.h"

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>

#include "renderers/sdf/scene_hash.h"
#include "renderers/sdf/sdf_cache.h"
#include "util/build_id.h"
#include "util/error.h"

namespace sdfbench::sdf {
namespace {

namespace fs = std::filesystem;

// The entry's file, or none when the store is off (or the executable has no build ID).
std::optional<fs::path> entry_path(uint64_t key) {
  const char* dir = std::getenv("SDFBENCH_BUILD_STORE");
  if (!dir || !*dir || executable_build_id().empty()) return std::nullopt;
  char name[32];
  std::snprintf(name, sizeof name, "%016llx.sdfcache", static_cast<unsigned long long>(key));
  return fs::path(dir) / executable_build_id() / name;
}

// The mesh alone, one instance where it stands: the scene an entry is the SDF cache of.
Scene mesh_scene(const Mesh& mesh) {
  Scene scene;
  scene.meshes.push_back(mesh);
  scene.instances.push_back(Instance{});
  return scene;
}

}  // namespace

std::optional<MeshDistanceGrid> load_stored_mesh_grid(const Mesh& mesh, const MeshGridParams& params, uint64_t key) {
  const std::optional<fs::path> path = entry_path(key);
  std::error_code ec;
  if (!path || !fs::is_regular_file(*path, ec)) return std::nullopt;
  try {
    const Scene scene = mesh_scene(mesh);
    SceneSdf stored = load_sdf_cache(*path, scene, params, one_cell_hash(scene));
    return std::move(stored.mesh_grids.at(0));
  } catch (const Error&) {
    return std::nullopt;  // a damaged or stale entry: built again, and replaced
  }
}

void store_mesh_grid(const Mesh& mesh, const MeshGridParams& params, uint64_t key, const MeshDistanceGrid& grid) {
  const std::optional<fs::path> path = entry_path(key);
  if (!path) return;
  try {
    fs::create_directories(path->parent_path());
    const Scene scene = mesh_scene(mesh);
    SceneSdf sdf;
    sdf.mesh_grids.push_back(grid);
    sdf.hash = build_scene_hash(scene, sdf.mesh_grids, one_cell_hash(scene));
    write_sdf_cache(*path, scene, sdf, params);
  } catch (const std::exception&) {
    // Unwritable folder, full disk: the next process builds the grid again.
  }
}

}  // namespace sdfbench::sdf
