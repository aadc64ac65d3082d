// Fuzz target for the SDF cache decoder. Every input must either decode or be refused with
// sdfbench::Error: any other exception, a crash, or (in this sanitized build) an out-of-bounds
// read or undefined behaviour fails the run.
//
// Built with AddressSanitizer + UBSan and run briefly by ctest through its own mutation driver
// (structure-aware: most mutants get a fresh checksum so they reach the structural checks).
// With clang, -DSDFBENCH_LIBFUZZER=ON builds the same entry point for libFuzzer instead.
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <stdexcept>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "renderers/sdf/sdf_cache_format.h"
#include "renderers/sdf_bricks/brick_field.h"
#include "renderers/sdf_global/global_field.h"
#include "util/error.h"

using sdfbench::Error;
namespace sdf = sdfbench::sdf;

static uint64_t accepted = 0, refused = 0;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    const sdf::SdfCacheContents c =
        sdf::decode_sdf_cache(std::span(reinterpret_cast<const std::byte*>(data), size), "fuzz input");
    // Walk what was accepted the way a renderer does: every index must be in range.
    const sdf::SceneHash& hash = c.sdf.hash;
    for (uint32_t root : hash.cell_root) {
      uint32_t node = root;
      while (hash.nodes.at(node).first_child >= 0) node = static_cast<uint32_t>(hash.nodes[node].first_child) + 7;
      const sdf::OctreeNode& leaf = hash.nodes[node];
      for (uint32_t k = 0; k < leaf.list_count; ++k) (void)hash.instance_lists.at(leaf.list_begin + k);
    }
    // The brick fields as sdf-bricks walks them: one per mesh, a stored brick's atlas samples.
    if (const sdf::BrickFields* bricks = c.sdf.find<sdf::BrickFields>()) {
      if (bricks->fields.size() != c.sdf.mesh_grids.size()) throw std::logic_error("brick fields do not match the meshes");
      for (const sdf::BrickField& f : bricks->fields)
        for (uint32_t slot : f.indirection)
          if (slot != sdf::kEmptyBrick) (void)f.atlas.at((size_t{slot} + 1) * sdf::kBrickSamples * sdf::bytes_per_sample(f.format) - 1);
    }
    // The global field as sdf-global walks it: a brick's atlas samples and its instance list.
    if (const sdf::GlobalFieldStructure* global = c.sdf.find<sdf::GlobalFieldStructure>()) {
      const sdf::GlobalField& g = global->field;
      const size_t brick_bytes = sdf::kBrickSamples * sdf::bytes_per_sample(g.field.format);
      for (uint32_t slot : g.field.indirection) {
        if (slot == sdf::kEmptyBrick) continue;
        (void)g.field.atlas.at((size_t{slot} + 1) * brick_bytes - 1);
        for (uint32_t k = g.list_begin.at(slot); k < g.list_begin.at(slot + 1); ++k)
          if (g.list_instances.at(k) >= c.instance_count) throw std::logic_error("a listed instance is out of range");
      }
      if (!g.field.coarse_at_centres || g.field.coarse.size() != size_t{g.field.bricks.x} * g.field.bricks.y * g.field.bricks.z)
        throw std::logic_error("the global coarse level does not match its bricks");
    }
    ++accepted;
  } catch (const Error&) {
    ++refused;
  }
  return 0;
}

#ifndef SDFBENCH_LIBFUZZER
namespace {

// The seed: a small valid cache built by hand and encoded by the format itself (so it follows the
// format's version; there is no seed file to regenerate): one mesh (2 triangles, 4 vertices, 2x2x2 cells) and a
// 2x1x1 hash whose first cell holds an octree of depth 1, and a brick field of 2x1x1 bricks
// (one stored, f16) and a global field of 1x1x2 bricks (one stored, f32, listing two instances) so
// that the brick and global sections are fuzzed too.
std::vector<std::byte> seed_cache() {
  sdf::SdfCacheContents c;
  c.scene_hash = 0x1234;
  c.instance_count = 3;
  sdf::SceneSdf& s = c.sdf;
  s.hash.params.hash_cell = 2.0f;
  s.hash.params.octree_depth = 1;
  sdf::MeshDistanceGrid g;
  g.origin = glm::vec3(-1.0f);
  g.cell_size = 1.0f;
  g.dims = glm::uvec3(2);
  g.cell_begin = {0, 1, 2, 4, 5, 6, 7, 8, 10};
  g.cell_triangles = {0, 1, 0, 1, 0, 1, 0, 1, 0, 1};
  g.face_normals = {glm::vec3(0, 0, 1), glm::vec3(0, 0, 1)};
  g.edge_normals.assign(6, glm::vec3(0, 0, 1));
  g.vertex_normals.assign(4, glm::vec3(0, 0, 1));
  s.mesh_grids = {g};
  c.mesh_triangles = {2};
  c.mesh_vertices = {4};
  s.hash.origin = glm::vec3(0.0f);
  s.hash.cell_size = 2.0f;
  s.hash.dims = glm::uvec3(2, 1, 1);
  s.hash.cell_root = {0, 9};
  s.hash.nodes.push_back({1, 0, 0, 0});
  for (uint32_t k = 0; k < 8; ++k) s.hash.nodes.push_back({-1, k % 3, 1, 1});
  s.hash.nodes.push_back({-1, 0, 3, 0});
  s.hash.instance_lists = {0, 1, 2};
  sdf::BrickField f;
  f.origin = glm::vec3(-1.5f);
  f.voxel = 0.25f;
  f.bricks = glm::uvec3(2, 1, 1);
  f.format = sdf::SdfFormat::f16;
  f.indirection = {0, sdf::kEmptyBrick};
  f.atlas.assign(sdf::kBrickSamples * 2, 0);  // half 0.0
  f.coarse.assign(12, 0.5f);
  s.set(sdf::BrickFields(sdf::BrickFieldParams{8, 2, sdf::SdfFormat::f16}, {f}));
  sdf::GlobalFieldParams gp;
  gp.voxel = 0.5f;
  gp.band = 2;
  gp.format = sdf::SdfFormat::f32;
  sdf::GlobalField global;
  global.voxel_request = 0.5f;
  global.field.origin = glm::vec3(-2.0f);
  global.field.voxel = 0.5f;
  global.field.bricks = glm::uvec3(1, 1, 2);
  global.field.format = sdf::SdfFormat::f32;
  global.field.indirection = {sdf::kEmptyBrick, 0};
  global.field.atlas.assign(sdf::kBrickSamples * 4, 0);  // 0.0f
  global.field.coarse_at_centres = true;
  global.field.coarse.assign(2, 0.25f);
  global.list_begin = {0, 2};
  global.list_instances = {0, 2};
  global.build_ms = 1.0;
  s.set(sdf::GlobalFieldStructure(gp, std::move(global)));
  return sdf::encode_sdf_cache(c);
}

void mutate(std::vector<std::byte>& b, std::mt19937_64& rng) {
  const int mutations = 1 + static_cast<int>(rng() % 4);
  for (int m = 0; m < mutations && !b.empty(); ++m) {
    const size_t at = rng() % b.size();
    switch (rng() % 7) {
      case 0: b[at] ^= std::byte{static_cast<unsigned char>(1u << (rng() % 8))}; break;
      case 1: b[at] = std::byte{static_cast<unsigned char>(rng())}; break;
      case 2: case 3: {  // an "interesting" 32-bit value at an aligned offset (counts, indices, floats)
        const uint32_t values[] = {0u, 1u, 7u, 8u, 0x7fffffffu, 0x80000000u, 0xffffffffu, 0x7fc00000u /* NaN */,
                                   0x7f800000u /* inf */, static_cast<uint32_t>(b.size()), static_cast<uint32_t>(rng())};
        const uint32_t v = values[rng() % std::size(values)];
        const size_t aligned = at & ~size_t{3};
        if (aligned + 4 <= b.size()) std::memcpy(b.data() + aligned, &v, 4);
        break;
      }
      case 4: {  // a 64-bit offset or count
        const uint64_t values[] = {0u, 8u, b.size(), b.size() - 8, uint64_t{1} << 62, ~uint64_t{0}, rng() % (b.size() + 64)};
        const uint64_t v = values[rng() % std::size(values)];
        const size_t aligned = at & ~size_t{7};
        if (aligned + 8 <= b.size()) std::memcpy(b.data() + aligned, &v, 8);
        break;
      }
      case 5: b.resize(at); break;  // truncate
      case 6: b.insert(b.begin() + static_cast<std::ptrdiff_t>(at), static_cast<size_t>(1 + rng() % 16), std::byte{0}); break;
    }
  }
  if (rng() % 10 < 8) sdf::reseal_sdf_cache(b);
}

}  // namespace

// usage: sdfbench_cache_fuzz [--seconds S] [--seed N|time]   (time: a new seed each run, printed first)
int main(int argc, char** argv) {
  double seconds = 5.0;
  uint64_t seed = 1;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::string(argv[i]) == "--seconds") seconds = std::atof(argv[i + 1]);
    else if (std::string(argv[i]) == "--seed" && std::string(argv[i + 1]) == "time")
      seed = static_cast<uint64_t>(std::chrono::system_clock::now().time_since_epoch().count());
    else if (std::string(argv[i]) == "--seed") seed = std::strtoull(argv[i + 1], nullptr, 10);
  }
  // First, so that a sanitizer's abort still leaves the seed that replays it (--seed N).
  std::fprintf(stderr, "cache fuzz: seed %llu\n", static_cast<unsigned long long>(seed));
  const std::vector<std::byte> seed_bytes = seed_cache();
  LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(seed_bytes.data()), seed_bytes.size());
  if (accepted != 1) {
    std::fprintf(stderr, "the seed cache was refused: the fuzz driver is broken\n");
    return 1;
  }
  std::mt19937_64 rng(seed);
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  uint64_t runs = 0;
  try {
    while (std::chrono::steady_clock::now() < end) {
      for (int k = 0; k < 256; ++k, ++runs) {
        std::vector<std::byte> input = seed_bytes;
        mutate(input, rng);
        LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(input.data()), input.size());
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "FAIL: decoder threw a non-Error exception: %s\n", e.what());
    return 1;
  }
  std::printf("%llu inputs (seed %llu): %llu refused with a clear error, %llu accepted\n",
              static_cast<unsigned long long>(runs), static_cast<unsigned long long>(seed),
              static_cast<unsigned long long>(refused), static_cast<unsigned long long>(accepted - 1));
  return 0;
}
#endif
