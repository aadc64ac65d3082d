// `sdfbench check-sdf`: the per-mesh distance grid against brute force over all triangles.
#include <algorithm>
#include <atomic>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "harness/cli_common.h"
#include "harness/commands.h"
#include "renderers/backend_registry.h"
#include "renderers/sdf/mesh_distance_grid.h"
#include "renderers/sdf/sdf_params.h"
#include "scenes/scene.h"
#include "scenes/mesh.h"
#include "scenes/mesh_file.h"
#include "scenes/named_mesh.h"
#include "scenes/mesh_resize.h"
#include "scenes/random.h"
#include "scenes/sized_mesh.h"
#include "util/error.h"

namespace sdfbench {
namespace {

struct CheckSdfArgs {
  std::string mesh, samples = "100000", seed = "1", tolerance = "1e-5", rule = "tight", subdivision = "2";
  BackendParams grid;  // --mesh-cell, --cells-per-extent, --fixed-grid: the backends' declarations
};

// The backends' parameters check-sdf takes as flags (their declarations: ranges, defaults, help),
// and what it reads of them: the mesh grid's (sdf::mesh_grid_params), --max-structure-mb at its
// default.
const char* const kGridFlags[] = {"mesh_cell", "cells_per_extent", "fixed_grid"};

BackendInfo mesh_grid_reader() {
  BackendInfo reader;
  reader.name = "check-sdf";
  for (const char* name : kGridFlags) reader.params.push_back(catalogue_spec(name));
  reader.params.push_back(catalogue_spec("max_structure_mb"));
  return reader;
}

uint64_t parse_integer(const std::string& text, const char* option, uint64_t lo, uint64_t hi) {
  uint64_t v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size() || v < lo || v > hi)
    throw Error(std::string(option) + " '" + text + "': expected an integer from " + std::to_string(lo) + " to " +
                std::to_string(hi));
  return v;
}

// A finite number > 0 (or >= 0 when zero_ok).
float parse_positive(const std::string& text, const char* option, bool zero_ok) {
  float v = 0.0f;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size() || !std::isfinite(v) || v < 0.0f ||
      (v == 0.0f && !zero_ok))
    throw Error(std::string(option) + " '" + text + "': expected a " + (zero_ok ? "non-negative" : "positive") +
                " number");
  return v;
}

Mesh load_mesh_argument(const std::string& text) {
  if (is_mesh_name(text)) return load_named_mesh(text);
  if (const size_t at = text.find('@'); at != std::string::npos && !builtin_mesh_path(text.substr(0, at)).empty())
    return load_sized_mesh(text.substr(0, at),
                           static_cast<uint32_t>(parse_integer(text.substr(at + 1), "--mesh's triangle count", kMinResizedTriangles,
                                                               kMaxResizedTriangles)));
  const std::filesystem::path path(text);
  if (!std::filesystem::is_regular_file(path))
    throw Error("--mesh '" + text + "': neither a named mesh (" + mesh_names_text() + ") nor an existing mesh file (" +
                mesh_file_extensions() + ")");
  Mesh mesh = load_mesh_file(path, path.stem().string());
  check_coordinates(mesh, "--mesh '" + text + "'");  // as a scene file's meshes are (kMaxCoordinate)
  return mesh;
}

glm::vec3 random_direction(Pcg32& rng) {
  for (;;) {
    const glm::vec3 v(rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f));
    const float len2 = glm::dot(v, v);
    if (len2 > 1e-4f && len2 <= 1.0f) return v / std::sqrt(len2);
  }
}

// 40% uniform in the grid box, 40% near the surface (a random point of a random triangle moved
// by up to two cells, biased towards the surface), 20% outside the grid box (up to half its size).
std::vector<glm::vec3> make_samples(const Mesh& mesh, const sdf::MeshDistanceGrid& grid, uint64_t count, uint64_t seed) {
  Pcg32 rng(seed);
  const glm::vec3 lo = grid.origin, hi = grid.box_max(), size = hi - lo;
  std::vector<glm::vec3> samples;
  samples.reserve(count);
  for (uint64_t i = 0; i < count; ++i) {
    const uint64_t kind = i % 5;
    glm::vec3 p;
    if (kind < 2) {
      p = glm::vec3(rng.uniform(lo.x, hi.x), rng.uniform(lo.y, hi.y), rng.uniform(lo.z, hi.z));
    } else if (kind < 4) {
      const glm::uvec3& t = mesh.triangles[rng.next() % mesh.triangles.size()];
      const float r1 = std::sqrt(rng.uniform()), r2 = rng.uniform();
      const glm::vec3 surface = (1.0f - r1) * mesh.positions[t.x] + r1 * (1.0f - r2) * mesh.positions[t.y] +
                                r1 * r2 * mesh.positions[t.z];
      const float u = rng.uniform();
      p = surface + random_direction(rng) * (2.0f * grid.cell_size * u * u * u);
    } else {
      p = glm::vec3(rng.uniform(lo.x, hi.x), rng.uniform(lo.y, hi.y), rng.uniform(lo.z, hi.z));
      const uint32_t axis = rng.next() % 3;
      const float beyond = rng.uniform(1e-3f, 0.5f) * size[axis];
      p[axis] = (rng.next() & 1u) ? hi[axis] + beyond : lo[axis] - beyond;
    }
    samples.push_back(p);
  }
  return samples;
}

// Runs body(i) for every sample in parallel, with a progress line on stderr when it takes long.
template <typename Body>
void for_samples(size_t count, const char* what, Body body) {
  const auto start = std::chrono::steady_clock::now();
  auto seconds = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  double reported = 0.0;
  constexpr size_t kChunk = 8192;
  for (size_t begin = 0; begin < count; begin += kChunk) {
    tbb::parallel_for(tbb::blocked_range<size_t>(begin, std::min(count, begin + kChunk), 64),
                      [&](const tbb::blocked_range<size_t>& r) {
                        for (size_t i = r.begin(); i < r.end(); ++i) body(i);
                      });
    if (seconds() - reported > 5.0) {
      reported = seconds();
      std::fprintf(stderr, "  %s: %zu/%zu samples, %.1f s\n", what, std::min(count, begin + kChunk), count, reported);
    }
  }
}

double elapsed_ms(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - since).count();
}

void run_check_sdf(const CheckSdfArgs& args) {
  const uint64_t sample_count = parse_integer(args.samples, "--samples", 1, 100000000);
  const uint64_t seed = parse_integer(args.seed, "--seed", 0, UINT64_MAX);
  const float tolerance = parse_positive(args.tolerance, "--tolerance", true);
  // The grid's flags were parsed by their declarations; resolved, they are the backends' record.
  const BackendParams grid_params = resolve_params(mesh_grid_reader(), args.grid);
  sdf::MeshGridParams params = sdf::mesh_grid_params(grid_params);
  if (params.cell_size != 0.0f && args.grid.has("cells_per_extent"))  // --cells-per-extent is used with --mesh-cell 0
    throw Error("--mesh-cell and --cells-per-extent both set the grid resolution: give one of them");
  params.subdivision = static_cast<uint32_t>(parse_integer(args.subdivision, "--subdivision", 1, 8));
  if (args.rule == "sphere")
    params.rule = sdf::MeshGridRule::sphere;
  else if (args.rule != "tight")
    throw Error("--rule '" + args.rule + "': expected tight or sphere");

  const auto wall_start = std::chrono::steady_clock::now();
  const Mesh mesh = load_mesh_argument(args.mesh);
  const glm::vec3 ext = mesh.bounds.extent();
  const float extent = std::max({ext.x, ext.y, ext.z, 1e-30f});
  const size_t open_edges = sdf::open_edge_count(mesh);
  const sdf::MeshDistanceGrid grid = sdf::build_mesh_distance_grid(mesh, params);

  uint32_t list_min = UINT32_MAX, list_max = 0;
  size_t far_cells = 0;
  for (size_t c = 0; c < grid.cell_count(); ++c) {
    if (grid.is_far(c)) {
      ++far_cells;  // a bound, no list
      continue;
    }
    const uint32_t n = grid.cell_begin[c + 1] - grid.cell_begin[c];
    list_min = std::min(list_min, n);
    list_max = std::max(list_max, n);
  }
  std::printf("mesh      %s (%s), %zu triangles, extent %g, %s\n", mesh.name.c_str(), mesh.source.string().c_str(),
              mesh.triangle_count(), extent,
              open_edges == 0 ? "closed" : (std::to_string(open_edges) + " open or non-manifold edges").c_str());
  std::printf("grid      %ux%ux%u = %zu cells, cell size %g (%s rule%s)\n", grid.dims.x, grid.dims.y, grid.dims.z,
              grid.cell_count(), grid.cell_size, args.rule.c_str(),
              params.rule == sdf::MeshGridRule::tight ? (", subdivision " + std::to_string(params.subdivision)).c_str() : "");
  const size_t listed = grid.cell_count() - far_cells;
  std::printf("lists     min %u, mean %.2f, max %u triangles per listed cell (%zu listed", listed ? list_min : 0,
              static_cast<double>(grid.cell_triangles.size()) / static_cast<double>(std::max<size_t>(listed, 1)), list_max, listed);
  if (far_cells) std::printf(", %zu far cells with a bound: a grid scaled for %zu triangles", far_cells, mesh.triangle_count());
  std::printf(")\n");
  std::printf("memory    %zu bytes (%.3f MB)\n", grid.bytes(), static_cast<double>(grid.bytes()) / 1e6);
  std::printf("build     %.1f ms\n", grid.build_ms);
  std::fflush(stdout);

  const std::vector<glm::vec3> samples = make_samples(mesh, grid, sample_count, seed);
  std::vector<float> grid_d(samples.size()), brute_d(samples.size());
  auto t0 = std::chrono::steady_clock::now();
  for_samples(samples.size(), "grid", [&](size_t i) { grid_d[i] = sdf::grid_distance(grid, mesh, samples[i]); });
  const double grid_ms = elapsed_ms(t0);
  t0 = std::chrono::steady_clock::now();
  for_samples(samples.size(), "brute force", [&](size_t i) { brute_d[i] = sdf::brute_force_distance(mesh, samples[i]); });
  const double brute_ms = elapsed_ms(t0);

  const glm::vec3 lo = grid.origin, hi = grid.box_max();
  auto inside_box = [&](const glm::vec3& p) { return glm::all(glm::greaterThanEqual(p, lo)) && glm::all(glm::lessThanEqual(p, hi)); };
  size_t inside = 0, outside = 0, outside_above = 0, far = 0, far_above = 0;
  double max_err = 0.0, sum_err = 0.0, max_outside_excess = 0.0, sum_ratio = 0.0, far_ratio = 0.0;
  std::vector<size_t> inside_indices;
  for (size_t i = 0; i < samples.size(); ++i) {
    if (sdf::in_far_cell(grid, samples[i])) {
      // A far cell's bound: positive and at most the true distance.
      ++far;
      inside_indices.push_back(i);
      far_above += grid_d[i] <= 0.0f || grid_d[i] > brute_d[i];
      far_ratio += grid_d[i] / brute_d[i];
    } else if (inside_box(samples[i])) {
      ++inside;
      inside_indices.push_back(i);
      const double err = std::abs(static_cast<double>(grid_d[i]) - brute_d[i]);
      max_err = std::max(max_err, err);
      sum_err += err;
    } else {
      ++outside;
      const double excess = static_cast<double>(grid_d[i]) - brute_d[i];
      max_outside_excess = std::max(max_outside_excess, excess);
      outside_above += excess > tolerance * extent;
      sum_ratio += brute_d[i] > 0.0f ? grid_d[i] / brute_d[i] : 1.0;
    }
  }
  std::printf("samples   %zu (seed %llu): %zu inside the grid box, %zu outside\n", samples.size(),
              static_cast<unsigned long long>(seed), inside, outside);
  std::printf("queries   grid %.1f ns/sample, brute force %.1f ns/sample (wall, all threads)\n",
              grid_ms * 1e6 / static_cast<double>(samples.size()), brute_ms * 1e6 / static_cast<double>(samples.size()));
  std::printf("inside    max |grid - brute| %.3g (%.3g of the extent), mean %.3g%s\n", max_err, max_err / extent,
              inside ? sum_err / static_cast<double>(inside) : 0.0, far ? " (listed cells)" : "");
  if (far)
    std::printf("far       bound in (0, brute force] for %zu of %zu samples in far cells, mean bound/brute %.3f\n", far - far_above, far,
                far_ratio / static_cast<double>(far));
  std::printf("outside   box bound <= brute force: %zu of %zu (max excess %.3g), mean bound/brute %.3f\n",
              outside - outside_above, outside, std::max(0.0, max_outside_excess),
              outside ? sum_ratio / static_cast<double>(outside) : 1.0);

  // The sign, against ray parity (independent: no grid, no pseudo-normals); closed meshes only.
  size_t sign_checked = 0, sign_disagree = 0, sign_skipped = 0;
  if (open_edges == 0) {
    const float near = 1e-6f * extent;
    std::vector<signed char> disagree(inside_indices.size(), 0), skipped(inside_indices.size(), 0);
    t0 = std::chrono::steady_clock::now();
    for_samples(inside_indices.size(), "ray parity", [&](size_t k) {
      const glm::vec3& p = samples[inside_indices[k]];
      const float sd = sdf::grid_signed_distance(grid, mesh, p);
      if (std::abs(sd) < near) {
        skipped[k] = 1;
        return;
      }
      disagree[k] = (sd < 0.0f) != sdf::ray_parity_inside(mesh, p);
    });
    for (size_t k = 0; k < inside_indices.size(); ++k) {
      sign_skipped += skipped[k];
      sign_disagree += disagree[k];
    }
    sign_checked = inside_indices.size() - sign_skipped;
    std::printf("sign      pseudo-normal sign = ray parity for %zu of %zu inside samples (%zu within 1e-6 extent of "
                "the surface not compared; %.1f s)\n",
                sign_checked - sign_disagree, sign_checked, sign_skipped, elapsed_ms(t0) / 1e3);
  } else {
    std::printf("sign      not checked: the mesh is not closed\n");
  }
  std::printf("time      %.1f s\n", elapsed_ms(wall_start) / 1e3);

  std::vector<std::string> failures;
  if (max_err > tolerance * extent)
    failures.push_back("inside the grid box, max |grid - brute force| " + std::to_string(max_err) + " > tolerance " +
                       std::to_string(tolerance) + " x extent " + std::to_string(extent));
  if (outside_above > 0)
    failures.push_back(std::to_string(outside_above) + " samples outside the grid box where the box bound exceeds brute force");
  if (sign_disagree > 0)
    failures.push_back(std::to_string(sign_disagree) + " inside samples where the pseudo-normal sign disagrees with ray parity");
  if (far_above > 0) failures.push_back(std::to_string(far_above) + " samples in far cells whose bound is not in (0, brute force]");
  if (listed && list_min == 0) failures.push_back("a listed cell with an empty triangle list");
  if (failures.empty()) {
    std::printf("result    PASS\n");
    return;
  }
  for (const std::string& f : failures) std::printf("result    FAIL: %s\n", f.c_str());
  std::fflush(stdout);
  throw CommandFailed{2};
}

}  // namespace

void register_check_sdf_command(CLI::App& app) {
  auto args = std::make_shared<CheckSdfArgs>();
  CLI::App* cmd = app.add_subcommand("check-sdf", "Check a mesh's exact distance grid against brute force over all triangles");
  cmd->add_option("--mesh", args->mesh, "a thesis mesh (bunny, teapot, monkey, sphere), a scan (armadillo, ...: harness/scripts/fetch_scanned_meshes.sh), a thesis mesh at a size (bunny@200000), or a mesh file (.obj, .ply, .off, .gltf, .glb)")->required();
  cmd->add_option("--samples", args->samples, "sample points (40% in the grid box, 40% near the surface, 20% outside)")
      ->capture_default_str();
  add_backend_param_options(*cmd, args->grid, [](const ParamSpec& spec) {
    return std::find(std::begin(kGridFlags), std::end(kGridFlags), spec.name) != std::end(kGridFlags);
  });
  cmd->add_option("--seed", args->seed, "PCG32 seed of the samples")->capture_default_str();
  cmd->add_option("--tolerance", args->tolerance, "pass if max |grid - brute force| <= tolerance x mesh extent")
      ->capture_default_str();
  cmd->add_option("--rule", args->rule, "list rule: tight (default) or sphere (docs/design.md's cheap bound, for comparison)")
      ->capture_default_str();
  cmd->add_option("--subdivision", args->subdivision, "tight rule: test each cell's S^3 sub-boxes too (1..8)")
      ->capture_default_str();
  cmd->callback([args] { run_check_sdf(*args); });
}

}  // namespace sdfbench
