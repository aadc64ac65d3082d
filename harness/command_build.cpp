// `sdfbench build`: build a scene's SDF structures and report their cost and shape.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <cstdio>
#include <iostream>

#include <sys/resource.h>

#include "harness/cli_common.h"
#include "harness/commands.h"
#include "harness/output_paths.h"
#include "renderers/sdf/scene_hash.h"
#include "renderers/sdf/sdf_cache.h"
#include "renderers/sdf/sdf_params.h"
#include "scenes/scene_source.h"
#include "util/atomic_file.h"
#include "util/error.h"

namespace sdfbench {
namespace {

struct BuildArgs {
  std::string scene, backend = "sdf-octree";
  BackendParams params;
  std::string cache;
};

struct ListStats {
  size_t min = 0, max = 0;
  double mean = 0;
};

ListStats leaf_list_stats(const sdf::SceneHash& hash) {
  ListStats s{SIZE_MAX, 0, 0.0};
  size_t leaves = 0;
  for (const sdf::OctreeNode& n : hash.nodes) {
    if (n.first_child >= 0) continue;
    s.min = std::min<size_t>(s.min, n.list_count);
    s.max = std::max<size_t>(s.max, n.list_count);
    s.mean += n.list_count;
    ++leaves;
  }
  if (leaves) s.mean /= static_cast<double>(leaves);
  else s.min = 0;
  return s;
}

// This process's peak resident memory so far (MB), as the kernel counts it.
double peak_memory_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // KiB on Linux
}

void run_build(const BuildArgs& args) {
  const auto wall_start = std::chrono::steady_clock::now();
  const BackendInfo& backend = backend_info(args.backend);
  if (!backend.scene_hash)
    throw Error("--backend " + args.backend + ": build makes the exact structures of " + backends_with(&BackendInfo::scene_hash) +
                " (mesh grids, scene hash, octrees); " + args.backend + " has no scene hash");
  check_params_taken(args.params, {args.backend});
  const BackendParams params = resolve_params(backend, args.params);
  const sdf::MeshGridParams mesh_grid = sdf::mesh_grid_params(params);
  const sdf::SceneHashParams scene_hash = sdf::scene_hash_params(params);
  if (!args.cache.empty()) check_output_path(args.cache, "--cache");
  const Scene scene = load_scene(args.scene);
  check_distinct_outputs({{"--cache", args.cache}}, scene_inputs(scene));
  sdf::scene_hash_dims(scene, scene_hash);  // refused before the mesh grids are built
  std::cout << "scene       " << describe_scene(scene) << "\n" << std::flush;
  sdf::SceneSdf sdf;
  for (const Mesh& mesh : scene.meshes) {
    sdf.mesh_grids.push_back(sdf::build_mesh_distance_grid(mesh, mesh_grid));
    const sdf::MeshDistanceGrid& g = sdf.mesh_grids.back();
    size_t longest = 0;
    for (size_t c = 0; c < g.cell_count(); ++c) longest = std::max<size_t>(longest, g.cell_begin[c + 1] - g.cell_begin[c]);
    std::printf("mesh grid   %-8s %ux%ux%u cells (%.4g), triangles/cell mean %.1f max %zu, %.2f MB, %.0f ms\n",
                mesh.name.c_str(), g.dims.x, g.dims.y, g.dims.z, g.cell_size,
                static_cast<double>(g.cell_triangles.size()) / static_cast<double>(g.cell_count()), longest,
                static_cast<double>(g.bytes()) / 1e6, g.build_ms);
    if (!g.far_distance.empty())
      std::printf("            scaled for %zu triangles: %u cells per extent, %zu of %zu cells far (a bound, no list)\n",
                  mesh.triangle_count(), sdf::effective_cells_per_extent(mesh_grid, mesh.triangle_count()), g.far_cell_count(),
                  g.cell_count());
  }
  std::fflush(stdout);
  sdf.hash = sdf::build_scene_hash(scene, sdf.mesh_grids, scene_hash);
  const sdf::SceneHash& h = sdf.hash;
  const ListStats lists = leaf_list_stats(h);
  std::printf("scene hash  %ux%ux%u = %zu cells of %.4g, %zu nodes (octree depth <= %u, %s lists)\n", h.dims.x, h.dims.y,
              h.dims.z, h.cell_count(), h.cell_size, h.nodes.size(), h.params.octree_depth,
              h.params.lists == sdf::ListRule::Exact ? "exact" : "thesis");
  std::printf("            instances per leaf min %zu mean %.2f max %zu, %.2f MB, %.0f ms\n", lists.min, lists.mean,
              lists.max, static_cast<double>(h.bytes()) / 1e6, h.build_ms);
  std::printf("total       %.1f s (scene, mesh grids, scene hash), peak memory %.0f MB\n",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count(), peak_memory_mb());
  std::fflush(stdout);
  if (args.cache.empty()) return;
  for (const Instance& instance : scene.instances) sdf.world_to_object.push_back(instance.transform.world_to_object());
  const auto start = std::chrono::steady_clock::now();
  sdf::write_sdf_cache(args.cache, scene, sdf, mesh_grid);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  std::printf("cache       %s: %.2f MB, written in %.0f ms\n", args.cache.c_str(),
              static_cast<double>(std::filesystem::file_size(args.cache)) / 1e6, ms);
}

}  // namespace

void register_build_command(CLI::App& app) {
  auto args = std::make_shared<BuildArgs>();
  CLI::App* cmd = app.add_subcommand("build", "Build a scene's SDF structures (mesh grids, scene hash, octrees) and report them");
  cmd->add_option("--scene", args->scene, "scene descriptor (.json) or generator, e.g. thesis:bunny:1000")->required();
  cmd->add_option("--backend", args->backend, "whose structures and defaults: one of " + backends_with(&BackendInfo::scene_hash))
      ->capture_default_str();
  // The structures' parameters (not the tracing's: build traces nothing).
  add_backend_param_options(*cmd, args->params, [](const ParamSpec& spec) { return spec.group == "SDF structures"; });
  cmd->add_option("--cache", args->cache, "write the structures to this cache file (atomically), for render --cache");
  cmd->callback([args] { run_build(*args); });
}

}  // namespace sdfbench
