// Microbenchmarks of the CPU SDF structures (issue 3): mesh distance grid build per thesis mesh,
// scene hash build for thesis:bunny:1000 in the thesis' two configurations, and CPU distance
// query throughput (items/s = queries/s). Run with harness/scripts/run_microbench.sh.
#include <map>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "renderers/sdf/scene_hash.h"
#include "scenes/random.h"
#include "scenes/scene_source.h"

namespace {

using namespace sdfbench;

const std::string kScene = "thesis:bunny:1000";  // a string: scene(kScene) binds no temporary
constexpr size_t kQueries = 4096;  // points per iteration: enough to average over cells/leaves

// Scenes and structures are built once and shared by the benchmarks that only read them
// (benchmarks run one after another on the main thread, so plain statics are enough).
const Scene& scene(const std::string& spec) {
  static std::map<std::string, Scene> cache;
  auto it = cache.find(spec);
  if (it == cache.end()) it = cache.emplace(spec, load_scene(spec)).first;
  return it->second;
}

const Mesh& mesh(const std::string& name) { return scene("thesis:" + name + ":1").meshes.at(0); }

const sdf::MeshDistanceGrid& mesh_grid(const std::string& name) {
  static std::map<std::string, sdf::MeshDistanceGrid> cache;
  auto it = cache.find(name);
  if (it == cache.end()) it = cache.emplace(name, sdf::build_mesh_distance_grid(mesh(name), {})).first;
  return it->second;
}

sdf::SceneHashParams hash_params(float cell, uint32_t depth) {
  sdf::SceneHashParams p;
  p.hash_cell = cell;
  p.octree_depth = depth;
  return p;
}

const sdf::SceneSdf& scene_sdf(float cell, uint32_t depth) {
  static std::map<std::pair<float, uint32_t>, sdf::SceneSdf> cache;
  auto it = cache.find({cell, depth});
  if (it == cache.end()) it = cache.emplace(std::pair{cell, depth}, sdf::build_scene_sdf(scene(kScene), {}, hash_params(cell, depth))).first;
  return it->second;
}

// Fixed-seed uniform points in a box grown by 10 % of its extent per side: mostly near the
// surface, some outside the mesh grid (the cheap path), like a sphere tracer's late steps.
glm::vec3 sample_near(const Aabb& box, Pcg32& rng) {
  const glm::vec3 lo = box.min - 0.1f * box.extent(), hi = box.max + 0.1f * box.extent();
  return {rng.uniform(lo.x, hi.x), rng.uniform(lo.y, hi.y), rng.uniform(lo.z, hi.z)};
}

std::vector<glm::vec3> mesh_points(const Mesh& m, size_t n) {
  Pcg32 rng(42);
  std::vector<glm::vec3> points(n);
  for (glm::vec3& p : points) p = sample_near(m.bounds, rng);
  return points;
}

// Near a random instance each: uniform points in the whole scene box would mostly be empty
// space, where a query costs a box distance and says little about the structure.
std::vector<glm::vec3> scene_points(const Scene& s, size_t n) {
  Pcg32 rng(42);
  std::vector<glm::vec3> points(n);
  for (glm::vec3& p : points) p = sample_near(s.world_bounds(s.instances[rng.next() % s.instances.size()]), rng);
  return points;
}

void BM_MeshGridBuild(benchmark::State& state, const std::string& name) {
  const Mesh& m = mesh(name);
  sdf::MeshDistanceGrid grid;
  for (auto _ : state) grid = sdf::build_mesh_distance_grid(m, sdf::MeshGridParams{});
  state.counters["cells"] = static_cast<double>(grid.cell_count());
  state.counters["triangles"] = static_cast<double>(m.triangle_count());
  state.counters["bytes"] = static_cast<double>(grid.bytes());
  state.counters["mean_list"] = static_cast<double>(grid.cell_triangles.size()) / static_cast<double>(grid.cell_count());
}

void BM_SceneBuild(benchmark::State& state, float cell, uint32_t depth) {
  const Scene& s = scene(kScene);
  std::vector<sdf::MeshDistanceGrid> grids;  // the mesh grids are not part of the scene level
  for (const Mesh& m : s.meshes) grids.push_back(sdf::build_mesh_distance_grid(m, {}));
  sdf::SceneHash hash;
  for (auto _ : state) hash = sdf::build_scene_hash(s, grids, hash_params(cell, depth));
  size_t leaves = 0, listed = 0;
  for (const sdf::OctreeNode& n : hash.nodes) {
    if (n.first_child >= 0) continue;
    ++leaves;
    listed += n.list_count;
  }
  state.counters["cells"] = static_cast<double>(hash.cell_count());
  state.counters["nodes"] = static_cast<double>(hash.nodes.size());
  state.counters["bytes"] = static_cast<double>(hash.bytes());
  state.counters["mean_per_leaf"] = leaves ? static_cast<double>(listed) / static_cast<double>(leaves) : 0.0;
}

void BM_MeshDistanceQuery(benchmark::State& state, const std::string& name) {
  const Mesh& m = mesh(name);
  const sdf::MeshDistanceGrid& grid = mesh_grid(name);
  const std::vector<glm::vec3> points = mesh_points(m, kQueries);
  for (auto _ : state)
    for (const glm::vec3& p : points) benchmark::DoNotOptimize(sdf::grid_distance(grid, m, p));
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * points.size()));
}

// The reference the grid replaces: every triangle per query (fewer points, it is ~1000x slower).
void BM_BruteForceDistance(benchmark::State& state, const std::string& name) {
  const Mesh& m = mesh(name);
  const std::vector<glm::vec3> points = mesh_points(m, 64);
  for (auto _ : state)
    for (const glm::vec3& p : points) benchmark::DoNotOptimize(sdf::brute_force_distance(m, p));
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * points.size()));
}

void BM_SceneDistanceQuery(benchmark::State& state, float cell, uint32_t depth) {
  const Scene& s = scene(kScene);
  const sdf::SceneSdf& sdf = scene_sdf(cell, depth);
  const std::vector<glm::vec3> points = scene_points(s, kQueries);
  uint64_t evaluations = 0;
  for (auto _ : state)
    for (const glm::vec3& p : points) {
      sdf::SceneDistance d = sdf::scene_distance(sdf, s, p);
      benchmark::DoNotOptimize(d.distance);  // a mutable lvalue: the const& overload is deprecated
      evaluations += d.evaluations;
    }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * points.size()));
  // Instance distances per query: what the octree saves over a plain hash.
  state.counters["evals_per_query"] = static_cast<double>(evaluations) / static_cast<double>(state.iterations() * points.size());
}

// Builds use TBB threads: report wall time, not the main thread's CPU time.
BENCHMARK_CAPTURE(BM_MeshGridBuild, bunny, "bunny")->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
BENCHMARK_CAPTURE(BM_MeshGridBuild, teapot, "teapot")->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
BENCHMARK_CAPTURE(BM_MeshGridBuild, monkey, "monkey")->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
BENCHMARK_CAPTURE(BM_MeshGridBuild, sphere, "sphere")->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
BENCHMARK_CAPTURE(BM_SceneBuild, cell10_octree4, 10.0f, 4u)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
BENCHMARK_CAPTURE(BM_SceneBuild, cell1_hash_only, 1.0f, 0u)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

BENCHMARK_CAPTURE(BM_MeshDistanceQuery, bunny, "bunny")->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_MeshDistanceQuery, teapot, "teapot")->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_MeshDistanceQuery, monkey, "monkey")->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_MeshDistanceQuery, sphere, "sphere")->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_BruteForceDistance, bunny, "bunny")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SceneDistanceQuery, cell10_octree4, 10.0f, 4u)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_SceneDistanceQuery, cell1_hash_only, 1.0f, 0u)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
