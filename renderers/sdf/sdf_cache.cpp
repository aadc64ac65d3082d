#include "renderers/sdf/sdf_cache.h"

#include <chrono>
#include <iostream>
#include <cstdio>
#include <optional>
#include <ostream>
#include <sstream>

#include "renderers/sdf/cache/section_codec.h"
#include "renderers/sdf/sdf_cache_format.h"
#include "util/atomic_file.h"
#include "util/error.h"
#include "util/fnv1a.h"
#include "util/input_file.h"

namespace sdfbench::sdf {
namespace {

namespace fs = std::filesystem;

// Bump when the builders change what they produce for the same input: old caches turn stale.
constexpr char kBuilderVersion[] = "sdfbench-sdf-builder-1";

template <class T>
uint64_t hash_items(uint64_t h, const std::vector<T>& items) {
  const uint64_t n = items.size();
  h = fnv1a64(std::as_bytes(std::span(&n, 1)), h);
  return fnv1a64(std::as_bytes(std::span(items)), h);
}

template <class T>
uint64_t hash_value(uint64_t h, const T& value) {
  return fnv1a64(std::as_bytes(std::span(&value, 1)), h);
}

std::string describe(const MeshGridParams& m) {
  std::ostringstream s;
  s << "--mesh-cell " << m.cell_size << " --cells-per-extent " << m.cells_per_extent << " margin " << m.margin_cells
    << " rule " << (m.rule == MeshGridRule::tight ? "tight" : "sphere") << " subdivision " << m.subdivision
    << (m.scale_with_triangles ? "" : " --fixed-grid");
  return s.str();
}

std::string describe(const SceneHashParams& p) {
  std::ostringstream s;
  s << "--hash-cell " << p.hash_cell << " --octree-depth " << p.octree_depth << " --octree-min-objects "
    << p.octree_min_objects << " --octree-min-size " << p.octree_min_size << " --lists "
    << (p.lists == ListRule::Exact ? "exact" : "thesis");
  return s.str();
}

bool same(const MeshGridParams& a, const MeshGridParams& b) {
  return a.cell_size == b.cell_size && a.cells_per_extent == b.cells_per_extent && a.margin_cells == b.margin_cells &&
         a.rule == b.rule && a.subdivision == b.subdivision && a.scale_with_triangles == b.scale_with_triangles;
}

bool same(const SceneHashParams& a, const SceneHashParams& b) {
  return a.hash_cell == b.hash_cell && a.octree_depth == b.octree_depth && a.octree_min_objects == b.octree_min_objects &&
         a.octree_min_size == b.octree_min_size && a.lists == b.lists;
}

}  // namespace

uint64_t scene_geometry_hash(const Scene& scene) {
  uint64_t h = fnv1a64(std::as_bytes(std::span(kBuilderVersion)));
  h = hash_value(h, static_cast<uint64_t>(scene.meshes.size()));
  for (const Mesh& mesh : scene.meshes) {
    h = hash_items(h, mesh.positions);
    h = hash_items(h, mesh.triangles);
  }
  h = hash_value(h, static_cast<uint64_t>(scene.instances.size()));
  for (const Instance& instance : scene.instances) {
    h = hash_value(h, instance.mesh);
    h = hash_value(h, instance.transform.translation);
    h = hash_value(h, instance.transform.rotation);
    h = hash_value(h, instance.transform.scale);
  }
  return h;
}

bool write_sdf_cache(const fs::path& path, const Scene& scene, const SceneSdf& sdf, const MeshGridParams& mesh_params,
                     bool warn_if_unwritable) {
  SdfCacheContents c;
  c.scene_hash = scene_geometry_hash(scene);
  c.instance_count = static_cast<uint32_t>(scene.instances.size());
  c.mesh_params = mesh_params;
  for (const Mesh& mesh : scene.meshes) {
    c.mesh_triangles.push_back(static_cast<uint32_t>(mesh.triangles.size()));
    c.mesh_vertices.push_back(static_cast<uint32_t>(mesh.positions.size()));
  }
  c.sdf = sdf;  // a copy for the encoder (world_to_object is not written)
  const std::vector<std::byte> bytes = encode_sdf_cache(c);
  if (bytes.size() > kMaxSdfCacheBytes)  // the loader would refuse it
    throw Error("SDF cache '" + path.string() + "' would be " + describe_bytes(bytes.size()) + ", more than the limit for a cache (" +
                describe_bytes(kMaxSdfCacheBytes) + "); not written (use a coarser --mesh-cell or --hash-cell)");
  try {
    write_file_atomically(path, bytes);
    return true;
  } catch (const Error& e) {
    if (!warn_if_unwritable) throw;
    // A cache that cannot be written (a read-only file system, a full disk) costs the next run a
    // build, not this one its render: said, and the render goes on (as the mesh cache does).
    std::cerr << "sdfbench: warning: " << e.what() << "; going on without updating the SDF cache\n";
    return false;
  }
}

namespace {

// The whole file, read once its header has been checked against its size.
std::vector<std::byte> read_cache(const InputFile& file, const fs::path& path) {
  check_sdf_cache_header(file.read_prefix(kSdfCacheHeaderBytes), file.size(), path.string());
  return file.read_all();
}

// A cache checked completely and against this scene, and the requested structures it lacks.
struct CachedSdf {
  SceneSdf sdf;
  StructureRequests missing;
};

// The cache already read (and bounded), checked completely and against this scene. A requested
// structure it lacks is an error unless `complete` (the caller then builds it).
CachedSdf sdf_from_cache(std::span<const std::byte> bytes, const fs::path& path, const Scene& scene,
                         const MeshGridParams& mesh_params, const SceneHashParams& hash_params, const StructureRequests& extras,
                         bool complete) {
  SdfCacheContents c = decode_sdf_cache(bytes, path.string());
  const std::string stale = "SDF cache '" + path.string() + "' is stale: ";
  if (c.scene_hash != scene_geometry_hash(scene))
    throw Error(stale + "it was built for different geometry (a different scene, meshes, transforms or sdfbench builder)");
  if (!same(c.mesh_params, mesh_params))
    throw Error(stale + "built with mesh grid " + describe(c.mesh_params) + ", requested " + describe(mesh_params));
  if (!same(c.sdf.hash.params, hash_params))
    throw Error(stale + "built with " + describe(c.sdf.hash.params) + ", requested " + describe(hash_params));
  // Implied by the geometry hash, but the renderers index meshes with these: check explicitly.
  bool counts_match = c.sdf.mesh_grids.size() == scene.meshes.size() && c.instance_count == scene.instances.size();
  for (size_t m = 0; counts_match && m < scene.meshes.size(); ++m)
    counts_match = c.mesh_triangles[m] == scene.meshes[m].triangles.size() && c.mesh_vertices[m] == scene.meshes[m].positions.size();
  if (!counts_match) throw Error(stale + "its mesh or instance counts differ from the scene's");
  // Values a build derives from others (the checksum is no authentication: a cache resealed with
  // changed values decodes): each mesh grid where the mesh's bounds and the parameters put it,
  // and what each requested structure's request checks (e.g. the global field's voxel).
  const std::string resealed = "SDF cache '" + path.string() + "' disagrees with itself: ";
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const MeshGridLayout layout = mesh_grid_layout(scene.meshes[m], mesh_params);
    const MeshDistanceGrid& grid = c.sdf.mesh_grids[m];
    if (grid.cell_size != layout.cell_size || grid.dims != layout.dims || grid.origin != layout.origin ||
        grid.far_distance.empty() == has_far_cells(mesh_params, scene.meshes[m].triangles.size()))
      throw Error(resealed + "mesh '" + scene.meshes[m].name + "''s grid has another cell size, origin, size or far-cell layout than "
                  "the mesh's bounds and " + describe(mesh_params) + " give (a cache edited and resealed?)");
  }
  for (const auto& extra : extras)
    if (const auto held = c.sdf.optional.find(extra->kind()); held != c.sdf.optional.end())
      if (const std::string disagrees = extra->disagrees(*held->second, scene); !disagrees.empty())
        throw Error(resealed + disagrees);
  CachedSdf cached;
  for (const auto& extra : extras) {
    const SectionCodec& codec = codec_for(*extra);
    if (const auto held = c.sdf.optional.find(extra->kind()); held != c.sdf.optional.end()) {
      if (const std::string differs = extra->differs(*held->second); !differs.empty()) throw Error(stale + differs);
      continue;
    }
    for (const StoredStructure& s : c.structures)
      if (s.kind == codec.kind)  // held, but in a layout this sdfbench does not read
        throw Error(stale + "it holds " + codec.name + " in codec version " + std::to_string(s.version) +
                    ", this sdfbench reads version " + std::to_string(codec.version));
    if (!complete) throw Error(stale + "it holds no " + codec.name + " (requested " + extra->describe() + ")");
    cached.missing.push_back(extra);
  }
  cached.sdf = std::move(c.sdf);
  for (const Instance& instance : scene.instances) cached.sdf.world_to_object.push_back(instance.transform.world_to_object());
  return cached;
}

}  // namespace

SceneSdf load_sdf_cache(const fs::path& path, const Scene& scene, const MeshGridParams& mesh_params,
                        const SceneHashParams& hash_params, const StructureRequests& extras) {
  return sdf_from_cache(read_cache(InputFile(path, "SDF cache", kMaxSdfCacheBytes), path), path, scene, mesh_params, hash_params,
                        extras, false)
      .sdf;
}

SceneSdf obtain_scene_sdf(const Scene& scene, const MeshGridParams& mesh_params, const SceneHashParams& hash_params,
                          const CacheOptions& cache, std::ostream& log, const StructureRequests& extras) {
  for (const auto& extra : extras) extra->validate();  // bad parameters are named before any cache is read
  if (cache.path.empty()) return build_scene_sdf(scene, mesh_params, hash_params, extras);
  const fs::path path = cache.path;
  std::error_code ec;
  if (fs::exists(path, ec)) {
    const auto start = std::chrono::steady_clock::now();
    // Outside the policy: a FIFO, device, directory or oversized file is no cache to replace.
    const InputFile file(path, "SDF cache", kMaxSdfCacheBytes);
    std::optional<CachedSdf> loaded;
    try {
      // A valid cache without a requested structure is completed, not stale: its exact
      // structures are what the fields are sampled from.
      loaded = sdf_from_cache(read_cache(file, path), path, scene, mesh_params, hash_params, extras, true);
    } catch (const Error& e) {
      if (cache.on_bad == BadCachePolicy::Refuse)
        throw Error(std::string(e.what()) + "; pass --on-bad-cache rebuild to replace it");
      log << "SDF cache: " << e.what() << "; rebuilding it\n";
    }
    if (loaded) {
      const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
      log << "SDF cache: loaded '" << path.string() << "' in " << static_cast<long>(ms) << " ms (build skipped)\n";
      // Outside the policy: a field that cannot be built (or a cache too big to write) is no bad cache.
      SceneSdf& sdf = loaded->sdf;
      for (const auto& extra : loaded->missing) extra->build(sdf, scene, mesh_params);
      if (!loaded->missing.empty() && write_sdf_cache(path, scene, sdf, mesh_params, true))
        for (const auto& extra : loaded->missing)
          log << "SDF cache: added " << codec_for(*extra).the_name << " (" << extra->describe() << ") to '" << path.string() << "'\n";
      return std::move(sdf);
    }
  }
  SceneSdf sdf = build_scene_sdf(scene, mesh_params, hash_params, extras);
  if (write_sdf_cache(path, scene, sdf, mesh_params, true)) log << "SDF cache: built and wrote '" << path.string() << "'\n";
  return sdf;
}

}  // namespace sdfbench::sdf
