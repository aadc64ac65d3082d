// The mesh distance grids in the cache: their build parameters, then per mesh a grid header
// (origin, cell size, dims, triangle/vertex counts, build ms), cell_begin, cell_triangles,
// face/edge/vertex pseudo-normals and, for a scaled grid (a mesh over kScaledGridFromTriangles),
// its far cells' bounds (version 2; version 1 held no scaled grids).
#include <algorithm>
#include <cstdio>

#include "renderers/sdf/cache/section_codec.h"
#include "renderers/sdf/cache/section_reader.h"
#include "renderers/sdf/cache/section_writer.h"
#include "renderers/sdf/cache/value_checks.h"
#include "renderers/sdf/sdf_cache_format.h"

namespace sdfbench::sdf {
namespace {

constexpr uint64_t kMaxMeshCells = 1ull << 26;  // build_mesh_distance_grid's own limit

struct ParamsRecord {
  float cell_size;
  uint32_t cells_per_extent;
  float margin_cells;
  uint32_t rule, subdivision, scale_with_triangles;
};
struct GridHeader {
  glm::vec3 origin;
  float cell_size;
  glm::uvec3 dims;
  uint32_t triangles, vertices, reserved;
  double build_ms;
};
static_assert(sizeof(ParamsRecord) == 24 && sizeof(GridHeader) == 48);
enum Section : uint32_t {
  kParams, kGridHeader, kCellBegin, kCellTriangles, kFaceNormals, kEdgeNormals, kVertexNormals, kFarDistance, kFarUpper
};

void encode(const SdfCacheContents& c, SectionWriter& out) {
  const MeshGridParams& p = c.mesh_params;
  out.add_one(kParams, 0, ParamsRecord{p.cell_size, p.cells_per_extent, p.margin_cells, static_cast<uint32_t>(p.rule), p.subdivision,
                                      p.scale_with_triangles ? 1u : 0u});
  for (uint32_t m = 0; m < c.sdf.mesh_grids.size(); ++m) {
    const MeshDistanceGrid& g = c.sdf.mesh_grids[m];
    out.add_one(kGridHeader, m, GridHeader{g.origin, g.cell_size, g.dims, c.mesh_triangles.at(m), c.mesh_vertices.at(m), 0, g.build_ms});
    out.add(kCellBegin, m, g.cell_begin);
    out.add(kCellTriangles, m, g.cell_triangles);
    out.add(kFaceNormals, m, g.face_normals);
    out.add(kEdgeNormals, m, g.edge_normals);
    out.add(kVertexNormals, m, g.vertex_normals);
    out.add(kFarDistance, m, g.far_distance);
    out.add(kFarUpper, m, g.far_upper);
  }
}

// Enum fields are checked as raw integers before they become enums.
MeshGridParams read_params(const SectionReader& in) {
  const ParamsRecord r = in.single<ParamsRecord>(kParams);
  in.require(r.rule <= static_cast<uint32_t>(MeshGridRule::sphere), "mesh grid rule parameter");
  in.require(std::isfinite(r.cell_size) && r.cell_size >= 0.0f, "mesh cell size parameter");
  in.require(r.cells_per_extent >= 1 && r.cells_per_extent <= 4096, "cells-per-extent parameter");
  in.require(std::isfinite(r.margin_cells) && r.margin_cells >= 0.0f, "mesh margin parameter");
  in.require(r.subdivision >= 1 && r.subdivision <= 8, "mesh grid subdivision parameter");
  in.require(r.scale_with_triangles <= 1, "mesh grid scale parameter");
  MeshGridParams p{r.cell_size, r.cells_per_extent, r.margin_cells, static_cast<MeshGridRule>(r.rule), r.subdivision};
  p.scale_with_triangles = r.scale_with_triangles == 1;
  return p;
}

MeshDistanceGrid read_grid(const SectionReader& in, uint32_t mesh, uint32_t& triangles, uint32_t& vertices) {
  const std::string what = "mesh " + std::to_string(mesh) + " grid";
  const GridHeader h = in.single<GridHeader>(kGridHeader, mesh);
  in.require(finite(h.origin) && positive_finite(h.cell_size), what + ": origin or cell size not finite");
  in.require(h.dims.x && h.dims.y && h.dims.z && cell_product(h.dims) <= kMaxMeshCells, what + ": bad dimensions");
  in.require(h.triangles >= 1 && h.vertices >= 3, what + ": no triangles");
  MeshDistanceGrid g;
  g.origin = h.origin;
  g.cell_size = h.cell_size;
  g.dims = h.dims;
  g.build_ms = h.build_ms;
  g.cell_begin = in.section<uint32_t>(kCellBegin, mesh);
  g.cell_triangles = in.section<uint32_t>(kCellTriangles, mesh);
  in.require(g.cell_begin.size() == cell_product(h.dims) + 1, what + ": cell_begin has " + std::to_string(g.cell_begin.size()) +
                                                                  " entries for " + std::to_string(cell_product(h.dims)) + " cells");
  in.require(g.cell_begin.front() == 0 && std::is_sorted(g.cell_begin.begin(), g.cell_begin.end()) &&
                 g.cell_begin.back() == g.cell_triangles.size(),
             what + ": cell_begin is not a valid prefix sum of the cell lists");
  in.require(std::all_of(g.cell_triangles.begin(), g.cell_triangles.end(), [&](uint32_t t) { return t < h.triangles; }),
             what + ": a cell lists a triangle index >= " + std::to_string(h.triangles));
  g.face_normals = in.section<glm::vec3>(kFaceNormals, mesh);
  g.edge_normals = in.section<glm::vec3>(kEdgeNormals, mesh);
  g.vertex_normals = in.section<glm::vec3>(kVertexNormals, mesh);
  in.require(g.face_normals.size() == h.triangles && g.edge_normals.size() == 3ull * h.triangles &&
                 g.vertex_normals.size() == h.vertices,
             what + ": pseudo-normal counts do not match its triangles and vertices");
  in.require(all_finite(g.face_normals) && all_finite(g.edge_normals) && all_finite(g.vertex_normals),
             what + ": non-finite pseudo-normal");
  // Far cells: none, or a bound per cell (0: a listed cell); a far cell lists nothing, and its
  // upper bound is finite and not below its bound's magnitude (the scene hash's lists rely on it).
  g.far_distance = in.section<float>(kFarDistance, mesh);
  g.far_upper = in.section<float>(kFarUpper, mesh);
  in.require((g.far_distance.empty() || g.far_distance.size() == cell_product(h.dims)) &&
                 g.far_upper.size() == g.far_distance.size(),
             what + ": far-cell bounds for " + std::to_string(g.far_distance.size()) + " of " +
                 std::to_string(cell_product(h.dims)) + " cells");
  for (size_t cell = 0; cell < g.far_distance.size(); ++cell) {
    const float d = g.far_distance[cell], u = g.far_upper[cell];
    in.require(std::isfinite(d) && std::isfinite(u), what + ": a non-finite far-cell bound");
    in.require(d == 0.0f || (g.cell_begin[cell] == g.cell_begin[cell + 1] && u >= std::abs(d)),
               what + ": far cell " + std::to_string(cell) + " has a list, or an upper bound below its bound");
  }
  triangles = h.triangles;
  vertices = h.vertices;
  return g;
}

void decode(const SectionReader& in, SdfCacheContents& c) {
  c.mesh_params = read_params(in);
  for (uint32_t m = 0; m < in.mesh_count(); ++m) {
    uint32_t triangles = 0, vertices = 0;
    c.sdf.mesh_grids.push_back(read_grid(in, m, triangles, vertices));
    c.mesh_triangles.push_back(triangles);
    c.mesh_vertices.push_back(vertices);
  }
}

std::vector<std::string> summary(const SdfCacheContents& c) {
  const MeshGridParams& m = c.mesh_params;
  char line[256];
  std::snprintf(line, sizeof line, "mesh grids   --mesh-cell %g --cells-per-extent %u, margin %g cells, rule %s, subdivision %u",
                m.cell_size, m.cells_per_extent, m.margin_cells, m.rule == MeshGridRule::tight ? "tight" : "sphere", m.subdivision);
  std::vector<std::string> lines{line};
  for (size_t i = 0; i < c.sdf.mesh_grids.size(); ++i) {
    const MeshDistanceGrid& g = c.sdf.mesh_grids[i];
    std::snprintf(line, sizeof line, "mesh %-7zu %ux%ux%u cells of %g, %u triangles, built in %.0f ms", i, g.dims.x, g.dims.y,
                  g.dims.z, g.cell_size, c.mesh_triangles[i], g.build_ms);
    lines.push_back(line);
  }
  return lines;
}

}  // namespace

const SectionCodec& mesh_grid_codec() {
  static const SectionCodec codec{
      .kind = 1, .name = "mesh grids", .version = 2,
      .sections = {{"mesh grid params", sizeof(ParamsRecord), false}, {"grid header", sizeof(GridHeader), true},
                   {"cell_begin", 4, true}, {"cell_triangles", 4, true}, {"face normals", 12, true},
                   {"edge normals", 12, true}, {"vertex normals", 12, true}, {"far distance", 4, true},
                   {"far upper", 4, true}},
      .the_name = "the mesh grids", .encode = encode, .decode = decode, .summary = summary,
  };
  return codec;
}

}  // namespace sdfbench::sdf
