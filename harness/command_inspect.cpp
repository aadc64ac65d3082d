// `sdfbench inspect FILE`: validate an SDF cache completely and describe it.
#include <cstdio>
#include <vector>

#include "harness/commands.h"
#include "renderers/sdf/sdf_cache_format.h"
#include "util/input_file.h"

namespace sdfbench {
namespace {

void run_inspect(const std::string& path) {
  // The header first: a file of gigabytes that is no cache is refused for its first bytes.
  const InputFile file(path, "SDF cache", sdf::kMaxSdfCacheBytes);
  const std::vector<std::byte> head = file.read_prefix(sdf::kSdfCacheHeaderBytes);
  sdf::check_sdf_cache_header(head, file.size(), path);
  const sdf::SdfCacheContents c = sdf::decode_sdf_cache(file.read_all(), path);
  const sdf::MeshGridParams& m = c.mesh_params;
  const sdf::SceneHashParams& h = c.hash_params;
  std::printf("file         %s (%llu bytes), valid\n", path.c_str(), static_cast<unsigned long long>(c.file_bytes));
  std::printf("version      %u\n", c.version);
  std::printf("scene hash   %016llx (%zu meshes, %u instances)\n", static_cast<unsigned long long>(c.scene_hash),
              c.mesh_grids.size(), c.instance_count);
  std::printf("mesh grids   --mesh-cell %g --cells-per-extent %u, margin %g cells, rule %s, subdivision %u\n", m.cell_size,
              m.cells_per_extent, m.margin_cells, m.rule == sdf::MeshGridRule::tight ? "tight" : "sphere", m.subdivision);
  std::printf("scene hash   --hash-cell %g --octree-depth %u --octree-min-objects %u --octree-min-size %g --lists %s\n",
              h.hash_cell, h.octree_depth, h.octree_min_objects, h.octree_min_size,
              h.lists == sdf::ListRule::Exact ? "exact" : "thesis");
  for (size_t i = 0; i < c.mesh_grids.size(); ++i) {
    const sdf::MeshDistanceGrid& g = c.mesh_grids[i];
    std::printf("mesh %-7zu %ux%ux%u cells of %g, %u triangles, built in %.0f ms\n", i, g.dims.x, g.dims.y, g.dims.z,
                g.cell_size, c.mesh_triangles[i], g.build_ms);
  }
  std::printf("hash         %ux%ux%u cells of %g, %zu octree nodes, built in %.0f ms\n", c.hash.dims.x, c.hash.dims.y,
              c.hash.dims.z, c.hash.cell_size, c.hash.nodes.size(), c.hash.build_ms);
  if (c.brick_params) {
    std::printf("brick fields %s\n", sdf::describe(*c.brick_params).c_str());
    for (size_t i = 0; i < c.brick_fields.size(); ++i) {
      const sdf::BrickField& f = c.brick_fields[i];
      std::printf("bricks %-5zu %ux%ux%u bricks of voxel %g, %zu stored, built in %.0f ms\n", i, f.bricks.x, f.bricks.y, f.bricks.z,
                  f.voxel, f.stored_bricks(), f.build_ms);
    }
  }
  if (c.global_params) {
    const sdf::GlobalField& g = c.global_field;
    const sdf::BrickField& f = g.field;
    std::printf("global field %s\n", sdf::describe(*c.global_params).c_str());
    std::printf("global       %ux%ux%u bricks of voxel %g from (%g, %g, %g), %zu stored, %zu list entries, built in %.0f ms\n",
                f.bricks.x, f.bricks.y, f.bricks.z, f.voxel, f.origin.x, f.origin.y, f.origin.z, f.stored_bricks(),
                g.list_instances.size(), g.build_ms);
  }
  std::printf("sections     %-28s %12s %12s %14s\n", "name", "offset", "elements", "bytes");
  for (const sdf::SdfCacheSection& s : c.sections)
    std::printf("             %-28s %12llu %12llu %14llu\n", s.name.c_str(), static_cast<unsigned long long>(s.offset),
                static_cast<unsigned long long>(s.count), static_cast<unsigned long long>(s.bytes));
}

}  // namespace

void register_inspect_command(CLI::App& app) {
  auto path = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("inspect", "Validate an SDF cache file completely and print its version, parameters, "
                                                "scene hash and sections (exit 1 when invalid)");
  cmd->add_option("file", *path, "cache written by `sdfbench build --cache`")->required();
  cmd->callback([path] { run_inspect(*path); });
}

}  // namespace sdfbench
