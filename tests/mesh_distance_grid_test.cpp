// The per-mesh exact distance grid: point-triangle distance, exactness against brute force,
// the pseudo-normal sign, the lists themselves, and `sdfbench check-sdf`.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "renderers/sdf/crossing_lists.h"
#include "renderers/sdf/exact_hit.h"
#include "renderers/sdf/mesh_distance_grid.h"
#include "renderers/sdf/triangle_distance.h"
#include "scenes/mesh.h"
#include "scenes/random.h"
#include "scenes/sized_mesh.h"
#include "tests/grid_equality.h"
#include "tests/test_support.h"
#include "util/error.h"

namespace sdfbench::sdf {
namespace {

float largest_extent(const Mesh& mesh) {
  const glm::vec3 e = mesh.bounds.extent();
  return std::max({e.x, e.y, e.z});
}

glm::vec3 random_direction(Pcg32& rng) {
  for (;;) {
    const glm::vec3 v(rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f));
    const float len2 = glm::dot(v, v);
    if (len2 > 1e-4f && len2 <= 1.0f) return v / std::sqrt(len2);
  }
}

glm::vec3 random_surface_point(const Mesh& mesh, Pcg32& rng) {
  const glm::uvec3& t = mesh.triangles[rng.next() % mesh.triangles.size()];
  const float r1 = std::sqrt(rng.uniform()), r2 = rng.uniform();
  return (1.0f - r1) * mesh.positions[t.x] + r1 * (1.0f - r2) * mesh.positions[t.y] + r1 * r2 * mesh.positions[t.z];
}

glm::vec3 random_in_box(const glm::vec3& lo, const glm::vec3& hi, Pcg32& rng) {
  return {rng.uniform(lo.x, hi.x), rng.uniform(lo.y, hi.y), rng.uniform(lo.z, hi.z)};
}

Mesh make_mesh(std::vector<glm::vec3> positions, std::vector<glm::uvec3> triangles) {
  Mesh mesh;
  mesh.name = "test";
  mesh.positions = std::move(positions);
  mesh.triangles = std::move(triangles);
  finish_mesh(mesh);
  return mesh;
}

// ---------------------------------------------------------------------------------------------
// closest_on_triangle

void expect_closest(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                    const glm::vec3& point, int feature) {
  const TriangleClosest r = closest_on_triangle(p, a, b, c);
  EXPECT_NEAR(r.point.x, point.x, 1e-6f);
  EXPECT_NEAR(r.point.y, point.y, 1e-6f);
  EXPECT_NEAR(r.point.z, point.z, 1e-6f);
  EXPECT_NEAR(r.distance_squared, glm::dot(p - point, p - point), 1e-6f);
  EXPECT_EQ(r.feature, feature);
}

TEST(ClosestOnTriangle, EveryFeatureRegion) {
  const glm::vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  expect_closest({0.2f, 0.2f, 1.0f}, a, b, c, {0.2f, 0.2f, 0.0f}, kFeatureFace);
  expect_closest({0.2f, 0.3f, -2.0f}, a, b, c, {0.2f, 0.3f, 0.0f}, kFeatureFace);
  expect_closest({0.5f, -1.0f, 0.5f}, a, b, c, {0.5f, 0.0f, 0.0f}, kFeatureEdge01);
  expect_closest({1.0f, 1.0f, 0.0f}, a, b, c, {0.5f, 0.5f, 0.0f}, kFeatureEdge12);
  expect_closest({-1.0f, 0.5f, 3.0f}, a, b, c, {0.0f, 0.5f, 0.0f}, kFeatureEdge20);
  expect_closest({-1.0f, -1.0f, 0.0f}, a, b, c, a, kFeatureVertex0);
  expect_closest({2.0f, -0.5f, 1.0f}, a, b, c, b, kFeatureVertex1);
  expect_closest({-0.5f, 2.0f, 0.0f}, a, b, c, c, kFeatureVertex2);
  expect_closest({0.25f, 0.25f, 0.0f}, a, b, c, {0.25f, 0.25f, 0.0f}, kFeatureFace);  // on the face: 0
}

TEST(ClosestOnTriangle, DegenerateTrianglesAreTheirEdges) {
  // Collinear: the segment from (0,0,0) to (2,0,0).
  const glm::vec3 a(0, 0, 0), b(1, 0, 0), c(2, 0, 0);
  TriangleClosest r = closest_on_triangle({1.5f, 1.0f, 0.0f}, a, b, c);
  EXPECT_FLOAT_EQ(r.distance_squared, 1.0f);
  EXPECT_NEAR(r.point.x, 1.5f, 1e-6f);
  EXPECT_TRUE(r.feature == kFeatureEdge12 || r.feature == kFeatureEdge20) << r.feature;
  r = closest_on_triangle({3.0f, 0.0f, 0.0f}, a, b, c);
  EXPECT_FLOAT_EQ(r.distance_squared, 1.0f);
  EXPECT_EQ(r.feature, kFeatureVertex2);
  // Two coincident vertices, and all three.
  r = closest_on_triangle({0.5f, 0.0f, 2.0f}, a, a, b);
  EXPECT_FLOAT_EQ(r.distance_squared, 4.0f);
  const glm::vec3 v(1, 1, 1);
  r = closest_on_triangle({1.0f, 1.0f, 3.0f}, v, v, v);
  EXPECT_FLOAT_EQ(r.distance_squared, 4.0f);
  EXPECT_GE(r.feature, kFeatureVertex0);
  EXPECT_FALSE(std::isnan(r.point.x));
}

TEST(ClosestOnTriangle, NoPointOfTheTriangleIsCloser) {
  Pcg32 rng(11);
  for (int i = 0; i < 300; ++i) {
    const glm::vec3 a = random_in_box(glm::vec3(-1), glm::vec3(1), rng), b = random_in_box(glm::vec3(-1), glm::vec3(1), rng),
                    c = random_in_box(glm::vec3(-1), glm::vec3(1), rng), p = random_in_box(glm::vec3(-2), glm::vec3(2), rng);
    const TriangleClosest r = closest_on_triangle(p, a, b, c);
    // The returned point lies on the triangle (barycentric sum = 1, all >= 0) ...
    const glm::vec3 n = glm::cross(b - a, c - a);
    EXPECT_NEAR(glm::dot(r.point - a, n), 0.0f, 1e-5f);
    // ... and no sampled point of the triangle is closer.
    float sampled = INFINITY;
    for (int u = 0; u <= 40; ++u)
      for (int v = 0; u + v <= 40; ++v) {
        const glm::vec3 q = a + (u / 40.0f) * (b - a) + (v / 40.0f) * (c - a);
        sampled = std::min(sampled, glm::dot(p - q, p - q));
      }
    EXPECT_LE(r.distance_squared, sampled + 1e-5f) << i;
    EXPECT_GE(std::sqrt(r.distance_squared), std::sqrt(sampled) - 0.1f) << i;  // samples are 1/40 apart
  }
}

// ---------------------------------------------------------------------------------------------
// Exactness against brute force

struct Counts {
  int inside = 0, outside = 0;
};

// 2000 points of each kind: near the surface, in cells far from it, on cell faces (including the
// grid box's max faces), outside the grid box.
Counts check_exact(const Mesh& mesh, const MeshDistanceGrid& grid, uint64_t seed) {
  Counts counts;
  Pcg32 rng(seed);
  const float extent = largest_extent(mesh), s = grid.cell_size;
  const glm::vec3 lo = grid.origin, hi = grid.box_max(), size = hi - lo;
  std::vector<glm::vec3> points;
  for (int i = 0; i < 2000; ++i) {
    const float u = rng.uniform();
    points.push_back(random_surface_point(mesh, rng) + random_direction(rng) * (2.0f * s * u * u * u));
  }
  for (int found = 0, tries = 0; found < 2000 && tries < 200000; ++tries) {
    const glm::uvec3 cell(rng.next() % grid.dims.x, rng.next() % grid.dims.y, rng.next() % grid.dims.z);
    const glm::vec3 cell_lo = lo + glm::vec3(cell) * s;
    if (grid_distance(grid, mesh, cell_lo + 0.5f * s) < 2.0f * s) continue;
    points.push_back(cell_lo + s * glm::vec3(rng.uniform(), rng.uniform(), rng.uniform()));
    ++found;
  }
  for (int i = 0; i < 2000; ++i) {
    glm::vec3 p = random_in_box(lo, hi, rng);
    const int snapped = 1 + static_cast<int>(rng.next() % 3);
    for (int k = 0; k < snapped; ++k) {
      const uint32_t axis = rng.next() % 3;
      p[axis] = lo[axis] + static_cast<float>(rng.next() % (grid.dims[axis] + 1)) * s;
    }
    points.push_back(p);
  }
  points.push_back(lo);
  points.push_back(hi);
  for (int i = 0; i < 2000; ++i) {
    glm::vec3 p = random_in_box(lo - 0.5f * size, hi + 0.5f * size, rng);
    const uint32_t axis = rng.next() % 3;
    p[axis] = (rng.next() & 1u) ? hi[axis] + rng.uniform(1e-4f, 0.5f) * size[axis] : lo[axis] - rng.uniform(1e-4f, 0.5f) * size[axis];
    points.push_back(p);
  }

  int wrong = 0;
  std::string first;
  for (const glm::vec3& p : points) {
    uint32_t grid_t = 0, brute_t = 0;
    const float g = grid_distance(grid, mesh, p, &grid_t);
    const float b = brute_force_distance(mesh, p, &brute_t);
    const bool in_box = glm::all(glm::greaterThanEqual(p, lo)) && glm::all(glm::lessThanEqual(p, hi));
    // Inside the box: exact (the listed minimum is the true one). Outside: the box distance, a
    // positive lower bound, and no triangle.
    const bool ok = in_box ? grid_t < mesh.triangle_count() && std::abs(g - b) <= 1e-6f * extent
                           : grid_t == UINT32_MAX && g > 0.0f && g <= b + 1e-6f * extent;
    (in_box ? counts.inside : counts.outside)++;
    if (!ok && wrong++ == 0)
      first = "p=(" + std::to_string(p.x) + ", " + std::to_string(p.y) + ", " + std::to_string(p.z) + ") " +
              (in_box ? "inside" : "outside") + ": grid " + std::to_string(g) + " (triangle " + std::to_string(grid_t) +
              "), brute force " + std::to_string(b) + " (triangle " + std::to_string(brute_t) + ")";
  }
  EXPECT_EQ(wrong, 0) << mesh.name << ", first: " << first;
  return counts;
}

void expect_valid_lists(const Mesh& mesh, const MeshDistanceGrid& grid) {
  ASSERT_EQ(grid.cell_begin.size(), grid.cell_count() + 1);
  EXPECT_EQ(grid.cell_begin.front(), 0u);
  EXPECT_EQ(grid.cell_begin.back(), grid.cell_triangles.size());
  for (size_t c = 0; c < grid.cell_count(); ++c) {
    ASSERT_LT(grid.cell_begin[c], grid.cell_begin[c + 1]) << mesh.name << ": cell " << c << " has an empty list";
    for (uint32_t i = grid.cell_begin[c]; i < grid.cell_begin[c + 1]; ++i) {
      ASSERT_LT(grid.cell_triangles[i], mesh.triangle_count());
      if (i > grid.cell_begin[c]) {
        ASSERT_LT(grid.cell_triangles[i - 1], grid.cell_triangles[i]);  // ascending
      }
    }
  }
  EXPECT_EQ(grid.face_normals.size(), mesh.triangle_count());
  EXPECT_EQ(grid.edge_normals.size(), 3 * mesh.triangle_count());
  EXPECT_EQ(grid.vertex_normals.size(), mesh.positions.size());
  EXPECT_EQ(grid.bytes(), (grid.cell_begin.size() + grid.cell_triangles.size()) * 4 +
                              (grid.face_normals.size() + grid.edge_normals.size() + grid.vertex_normals.size()) * 12);
}

TEST(MeshDistanceGrid, ExactOnTheThesisMeshesCoarseAndFine) {
  uint64_t seed = 1;
  for (const std::string& name : thesis_mesh_names()) {
    const Mesh mesh = load_obj(builtin_mesh_path(name), name);
    MeshGridParams coarse;
    coarse.cells_per_extent = 6;
    MeshGridParams fine;
    fine.cells_per_extent = 40;
    fine.margin_cells = 1.5f;
    for (const MeshGridParams& params : {coarse, fine}) {
      const MeshDistanceGrid grid = build_mesh_distance_grid(mesh, params);
      SCOPED_TRACE(name + " " + std::to_string(params.cells_per_extent) + " cells per extent");
      EXPECT_NEAR(std::max({grid.dims.x, grid.dims.y, grid.dims.z}) * grid.cell_size,
                  largest_extent(mesh) + 2.0f * params.margin_cells * grid.cell_size, 1.001f * grid.cell_size);
      expect_valid_lists(mesh, grid);
      const Counts counts = check_exact(mesh, grid, seed++);
      EXPECT_GT(counts.inside, 5900);
      EXPECT_GT(counts.outside, 1900);
    }
  }
}

// The fields' sampling query (ExactMeshDistance): beyond the grid's box, where the grid gives only a
// bound, the brute-force distance exactly (the same min over the same per-triangle distances),
// positive (outside the mesh's bounds); in the box the grid's own values, signed as the grid signs.
TEST(MeshDistanceGrid, ExactQueryIsBruteForceBeyondTheBoxAndTheGridInIt) {
  for (const std::string& name : thesis_mesh_names()) {
    SCOPED_TRACE(name);
    const Mesh mesh = load_obj(builtin_mesh_path(name), name);
    const MeshDistanceGrid grid = build_mesh_distance_grid(mesh, MeshGridParams{});
    const ExactMeshDistance exact(grid, mesh);
    const glm::vec3 size = grid.box_max() - grid.origin;
    Pcg32 rng(11);
    int beyond = 0, lower_bound = 0;
    for (int i = 0; i < 400; ++i) {
      // Within a box 3x the grid's, so most points lie beyond it; some just beyond a face.
      glm::vec3 p = random_in_box(grid.origin - size, grid.box_max() + size, rng);
      if (i % 4 == 0) p = random_surface_point(mesh, rng) + random_direction(rng) * (0.3f * size.x);
      const glm::vec3 q = glm::clamp(p, grid.origin, grid.box_max());
      const float brute = brute_force_distance(mesh, p);
      if (q != p) {
        ++beyond;
        EXPECT_EQ(exact.distance(p), brute) << "beyond the box at " << p.x << " " << p.y << " " << p.z;
        EXPECT_EQ(exact.signed_distance(p), brute);
        // A bound at or above the distance changes nothing; one below it gives +infinity.
        EXPECT_EQ(exact.signed_distance(p, brute), brute);
        EXPECT_EQ(exact.distance(p, 2.0f * brute), brute);
        EXPECT_EQ(exact.signed_distance(p, 0.99f * brute), std::numeric_limits<float>::infinity());
        lower_bound += grid_distance(grid, mesh, p) < brute;  // what the grid alone gives there
      } else {
        EXPECT_EQ(exact.distance(p), grid_distance(grid, mesh, p));
        EXPECT_EQ(exact.signed_distance(p), grid_signed_distance(grid, mesh, p));
        EXPECT_EQ(exact.signed_distance(p, 0.0f), grid_signed_distance(grid, mesh, p));  // the grid's, bound or not
      }
    }
    EXPECT_GT(beyond, 200);
    EXPECT_GT(lower_bound, 100);  // the query answers where the grid could not
  }
}

// A 50k-triangle mesh (the mesh-size axis' generator, cached in a temporary folder): its grid is
// scaled (mesh_distance_grid.h), exact in every listed cell (max |grid - brute force| = 0 on
// sampled points), a positive lower bound in far cells, with the sign of ray parity there; with
// --fixed-grid the plain grid, exact everywhere in the box.
TEST(MeshDistanceGrid, ScaledGridOnA50kTriangleMeshIsExactWhereItLists) {
  const test::TempDir dir;
  ::setenv("SDFBENCH_MESH_CACHE", dir.path().c_str(), 1);
  const Mesh mesh = load_sized_mesh("bunny", 50000);
  ASSERT_NEAR(static_cast<double>(mesh.triangle_count()), 50000.0, 500.0);
  const bool closed = open_edge_count(mesh) == 0;
  MeshGridParams fixed;
  fixed.scale_with_triangles = false;
  for (const MeshGridParams& params : {MeshGridParams{}, fixed}) {
    const MeshDistanceGrid grid = build_mesh_distance_grid(mesh, params);
    const bool scaled = params.scale_with_triangles;
    SCOPED_TRACE(scaled ? "scaled" : "fixed");
    EXPECT_EQ(std::max({grid.dims.x, grid.dims.y, grid.dims.z}) - 2, scaled ? 79u : 32u);  // 32 sqrt(50000 / 8192), + margins
    EXPECT_EQ(grid.far_distance.empty(), !scaled);
    Pcg32 rng(50000);
    const glm::vec3 lo = grid.origin, hi = grid.box_max();
    float max_error = 0.0f;
    int far = 0, far_bad = 0, sign_bad = 0;
    for (int i = 0; i < 600; ++i) {
      // Half near the surface, half anywhere in the grid box.
      const float u = rng.uniform();
      glm::vec3 p = i % 2 ? random_in_box(lo, hi, rng) : random_surface_point(mesh, rng) + random_direction(rng) * (2.0f * grid.cell_size * u * u);
      p = glm::clamp(p, lo, hi);
      const float g = grid_distance(grid, mesh, p), b = brute_force_distance(mesh, p);
      if (in_far_cell(grid, p)) {
        ++far;
        far_bad += !(g > 0.0f && g <= b && grid_upper_distance(grid, mesh, p) >= b);
        sign_bad += closed && (grid_signed_distance(grid, mesh, p) < 0.0f) != ray_parity_inside(mesh, p);
      } else {
        max_error = std::max(max_error, std::abs(g - b));
      }
    }
    EXPECT_EQ(max_error, 0.0f);
    EXPECT_EQ(far_bad, 0) << far << " far samples";
    EXPECT_EQ(sign_bad, 0) << far << " far samples";
    if (scaled) {
      EXPECT_GT(far, 100);
    }
  }
}

TEST(MeshDistanceGrid, ExactWithTheSphereRuleAndDeeperSubdivision) {
  const Mesh mesh = load_obj(builtin_mesh_path("monkey"), "monkey");
  MeshGridParams sphere_rule;
  sphere_rule.cells_per_extent = 12;
  sphere_rule.rule = MeshGridRule::sphere;
  MeshGridParams deep;
  deep.cells_per_extent = 12;
  deep.subdivision = 3;
  MeshGridParams flat;
  flat.cells_per_extent = 12;
  flat.subdivision = 1;
  const MeshDistanceGrid loose = build_mesh_distance_grid(mesh, sphere_rule), tight = build_mesh_distance_grid(mesh, deep),
                         single = build_mesh_distance_grid(mesh, flat);
  for (const MeshDistanceGrid* grid : {&loose, &tight, &single}) {
    expect_valid_lists(mesh, *grid);
    check_exact(mesh, *grid, 99);
  }
  // Every test of the tight rule only removes triangles the sphere rule lists: subsets, shorter.
  EXPECT_LT(tight.cell_triangles.size(), single.cell_triangles.size());
  EXPECT_LT(single.cell_triangles.size(), loose.cell_triangles.size());
  for (size_t c = 0; c < loose.cell_count(); ++c)
    EXPECT_TRUE(std::includes(loose.cell_triangles.begin() + loose.cell_begin[c], loose.cell_triangles.begin() + loose.cell_begin[c + 1],
                              single.cell_triangles.begin() + single.cell_begin[c],
                              single.cell_triangles.begin() + single.cell_begin[c + 1]))
        << c;
}

TEST(MeshDistanceGrid, ExactOnSmallAndDegenerateMeshes) {
  // One flat triangle (zero z extent), a zero-area triangle next to it, an explicit cell size.
  const Mesh flat = make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 2, 0}, {3, 3, 0}, {4, 4, 0}}, {{0, 1, 2}, {3, 4, 5}});
  MeshGridParams params;
  params.cell_size = 0.3f;
  const MeshDistanceGrid grid = build_mesh_distance_grid(flat, params);
  EXPECT_EQ(grid.dims.z, 2u);  // zero extent + one margin cell per side
  expect_valid_lists(flat, grid);
  check_exact(flat, grid, 5);
  // A query on the max corner and faces of the grid box is inside (the cell index is clamped).
  uint32_t t = UINT32_MAX;
  grid_distance(grid, flat, grid.box_max(), &t);
  EXPECT_LT(t, 2u);
}

TEST(MeshDistanceGrid, BuildIsDeterministic) {
  const Mesh mesh = load_obj(builtin_mesh_path("teapot"), "teapot");
  MeshGridParams params;
  params.cells_per_extent = 20;
  test::expect_same_grid(build_mesh_distance_grid(mesh, params), build_mesh_distance_grid(mesh, params));
}

TEST(MeshDistanceGrid, BadParametersAreErrors) {
  const Mesh mesh = load_obj(builtin_mesh_path("sphere"), "sphere");
  MeshGridParams p;
  p.cell_size = -1.0f;
  EXPECT_THROW(build_mesh_distance_grid(mesh, p), Error);
  p.cell_size = NAN;
  EXPECT_THROW(build_mesh_distance_grid(mesh, p), Error);
  p.cell_size = 1e-5f;  // 200000^3 cells
  EXPECT_THROW(build_mesh_distance_grid(mesh, p), Error);
  p = {};
  p.cells_per_extent = 0;
  EXPECT_THROW(build_mesh_distance_grid(mesh, p), Error);
  p = {};
  p.margin_cells = -1.0f;
  EXPECT_THROW(build_mesh_distance_grid(mesh, p), Error);
  p = {};
  p.subdivision = 0;
  EXPECT_THROW(build_mesh_distance_grid(mesh, p), Error);
}

// ---------------------------------------------------------------------------------------------
// Sign

TEST(MeshDistanceGrid, SignOnTheSphere) {
  const Mesh mesh = load_obj(builtin_mesh_path("sphere"), "sphere");
  ASSERT_EQ(open_edge_count(mesh), 0u);
  const MeshDistanceGrid grid = build_mesh_distance_grid(mesh, {});
  const glm::vec3 centre = mesh.bounds.center();
  Pcg32 rng(3);
  for (int i = 0; i < 2000; ++i) {
    // The polyhedron is convex around its centre: scaled-down surface points are inside,
    // scaled-up ones outside. Half of them close to the surface.
    const glm::vec3 surface = random_surface_point(mesh, rng);
    const float shrink = i % 2 ? rng.uniform(0.0f, 0.98f) : rng.uniform(0.98f, 0.9999f);
    const float grow = i % 2 ? rng.uniform(1.02f, 1.5f) : rng.uniform(1.0001f, 1.02f);
    EXPECT_LT(grid_signed_distance(grid, mesh, centre + shrink * (surface - centre)), 0.0f) << i;
    EXPECT_GT(grid_signed_distance(grid, mesh, centre + grow * (surface - centre)), 0.0f) << i;
  }
  // Near vertices and edges (where the face normal alone would fail): along the vertex normals.
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    const glm::vec3 n = glm::normalize(mesh.positions[v] - centre);
    EXPECT_LT(grid_signed_distance(grid, mesh, mesh.positions[v] - 1e-3f * n), 0.0f) << v;
    EXPECT_GT(grid_signed_distance(grid, mesh, mesh.positions[v] + 1e-3f * n), 0.0f) << v;
  }
  // Magnitude is the unsigned distance.
  const glm::vec3 p = centre + 0.5f * (mesh.positions[0] - centre);
  EXPECT_FLOAT_EQ(-grid_signed_distance(grid, mesh, p), grid_distance(grid, mesh, p));
  EXPECT_GT(grid_signed_distance(grid, mesh, grid.box_max() + 1.0f), 0.0f);
}

TEST(MeshDistanceGrid, SignOnTheBunnyAgreesWithRayParity) {
  const Mesh mesh = load_obj(builtin_mesh_path("bunny"), "bunny");
  ASSERT_EQ(open_edge_count(mesh), 0u);
  const MeshDistanceGrid grid = build_mesh_distance_grid(mesh, {});
  Pcg32 rng(4);
  int inside = 0, outside = 0;
  for (int i = 0; i < 1500; ++i) {
    // Half near the surface (the hard cases for the pseudo-normals), half anywhere in the box.
    const float u = rng.uniform();
    const glm::vec3 p = i % 2 ? random_in_box(grid.origin, grid.box_max(), rng)
                              : random_surface_point(mesh, rng) + random_direction(rng) * (0.05f * u * u);
    const float d = grid_signed_distance(grid, mesh, p);
    if (std::abs(d) < 1e-6f) continue;
    const bool parity_inside = ray_parity_inside(mesh, p);
    EXPECT_EQ(d < 0.0f, parity_inside) << "p=(" << p.x << ", " << p.y << ", " << p.z << ") d=" << d;
    (parity_inside ? inside : outside)++;
  }
  EXPECT_GT(inside, 300);
  EXPECT_GT(outside, 300);
}

TEST(MeshTopology, OpenEdges) {
  EXPECT_EQ(open_edge_count(load_obj(builtin_mesh_path("sphere"), "sphere")), 0u);
  EXPECT_EQ(open_edge_count(load_obj(builtin_mesh_path("bunny"), "bunny")), 0u);
  EXPECT_GT(open_edge_count(load_obj(builtin_mesh_path("teapot"), "teapot")), 0u);
  EXPECT_EQ(open_edge_count(make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}})), 3u);
  // A tetrahedron written with split (duplicated) vertices is still closed after welding.
  const Mesh tet = make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, 0}, {0, 0, 1},
                              {1, 0, 0}, {1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
                             {{0, 2, 1}, {3, 5, 4}, {6, 8, 7}, {9, 11, 10}});
  EXPECT_EQ(open_edge_count(tet), 0u);
  const MeshDistanceGrid grid = build_mesh_distance_grid(tet, {});
  EXPECT_LT(grid_signed_distance(grid, tet, glm::vec3(0.1f)), 0.0f);
  EXPECT_GT(grid_signed_distance(grid, tet, glm::vec3(0.5f)), 0.0f);
  EXPECT_GT(grid_signed_distance(grid, tet, glm::vec3(-0.01f, 0.2f, 0.2f)), 0.0f);
}

// ---------------------------------------------------------------------------------------------
// sdfbench check-sdf

TEST(CheckSdfCommand, PassesOnABuiltinMeshAndAUserObj) {
  test::CommandResult r = test::run_sdfbench("check-sdf --mesh sphere --samples 3000");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  for (const char* words : {"768 triangles", "cells", "lists", "build", "max |grid - brute| 0", "PASS"})
    EXPECT_NE(r.output.find(words), std::string::npos) << words << "\n" << r.output;
  test::TempDir dir;
  const auto obj = dir.write("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0.2\nv 0 1 0\nf 1 2 3 4\n");
  r = test::run_sdfbench("check-sdf --mesh " + obj.string() + " --samples 2000 --cells-per-extent 8 --seed 5");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("not closed"), std::string::npos) << r.output;
}

// The failure path: a closed tetrahedron with one face wound the wrong way. Distances stay exact,
// but the pseudo-normal sign disagrees with ray parity, so the check must fail with exit 2.
TEST(CheckSdfCommand, InconsistentOrientationFailsWithExitTwo) {
  test::TempDir dir;
  const std::string vertices = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\n";
  const auto good = dir.write("good.obj", vertices + "f 2 3 4\n");
  const auto flipped = dir.write("flipped.obj", vertices + "f 2 4 3\n");
  test::CommandResult r = test::run_sdfbench("check-sdf --mesh " + good.string() + " --samples 2000 --cells-per-extent 8");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  r = test::run_sdfbench("check-sdf --mesh " + flipped.string() + " --samples 2000 --cells-per-extent 8");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("FAIL: "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("sign disagrees with ray parity"), std::string::npos) << r.output;
}

TEST(CheckSdfCommand, BadArgumentsAreClearErrors) {
  const std::pair<std::string, std::string> cases[] = {
      {"--mesh cube", "neither a named mesh"},
      {"--mesh /nonexistent/x.obj", "nor an existing mesh file"},
      {"--mesh sphere --samples 0", "--samples"},
      {"--mesh sphere --samples ten", "--samples"},
      {"--mesh sphere --mesh-cell -1", "--mesh-cell"},
      {"--mesh sphere --mesh-cell 0.00001", "2^26 cells"},
      {"--mesh sphere --cells-per-extent 0", "--cells-per-extent"},
      {"--mesh sphere --tolerance x", "--tolerance"},
      {"--mesh sphere --rule fast", "--rule"},
      {"--mesh sphere --mesh-cell 0.1 --cells-per-extent 8", "give one of them"},
  };
  for (const auto& [args, words] : cases) {
    const test::CommandResult r = test::run_sdfbench("check-sdf " + args);
    EXPECT_EQ(r.exit_code, 1) << args << "\n" << r.output;
    EXPECT_NE(r.output.find("sdfbench: error:"), std::string::npos) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(words), std::string::npos) << args << "\n" << r.output;
  }
}

// A segment that starts at t = 0 on a cell wall and leaves the cell the point rounds into (a
// shadow ray leaving its surface): the walk must move on to the cell it enters and find the
// crossing beyond, not pick the cell behind again until kExactMaxCells runs out.
TEST(ExactCrossing, SegmentStartingOnACellWallMovesOn) {
  // A quad in the plane x = -0.5 and one at x = 1 (so the grid spans both); cells of 0.25, all
  // coordinates multiples of 0.25 so that the walls are exact.
  const Mesh mesh = make_mesh({{-0.5f, -1, -1}, {-0.5f, 1, -1}, {-0.5f, 1, 1}, {-0.5f, -1, 1},
                               {1, -1, -1}, {1, 1, -1}, {1, 1, 1}, {1, -1, 1}},
                              {{0, 1, 2}, {0, 2, 3}, {4, 6, 5}, {4, 7, 6}});
  MeshGridParams params;
  params.cell_size = 0.25f;
  const MeshDistanceGrid grid = build_mesh_distance_grid(mesh, params);
  const MeshCrossingLists lists = make_crossing_lists(grid, mesh);
  const glm::vec3 o(grid.origin.x + 3.0f * grid.cell_size, 0.1f, 0.1f), d(-1, 0, 0);
  // The precondition of the case: o rounds into the cell on the wall's +x side.
  ASSERT_EQ(std::floor((o.x - grid.origin.x) / grid.cell_size), 3.0f);
  Crossing crossing;
  uint32_t tests = 0;
  ASSERT_TRUE(exact_crossing(grid, lists, mesh, o, d, 0.0f, 10.0f, crossing, tests));
  EXPECT_FLOAT_EQ(crossing.t, o.x + 0.5f);
  EXPECT_LT(tests, 64u);  // a handful of cells, not kExactMaxCells visits of one
}

}  // namespace
}  // namespace sdfbench::sdf
