// The SDF cache: a bit-identical round trip, and a clear Error (never a crash, never structures)
// for stale, truncated, bit-flipped, random and hostile (re-checksummed) files, from every
// loader: decode (inspect), load_sdf_cache, obtain_scene_sdf, and the CLI.
#include <gtest/gtest.h>

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <fstream>
#include <sstream>

#include "renderers/sdf/build_reuse.h"
#include "renderers/sdf/cache/section_codec.h"
#include "renderers/sdf/sdf_cache.h"
#include "renderers/sdf/sdf_cache_format.h"
#include "renderers/sdf_bricks/brick_field.h"
#include "renderers/sdf_global/global_field.h"
#include "scenes/mesh.h"
#include "scenes/random.h"
#include "scenes/scene_source.h"
#include "tests/grid_equality.h"
#include "tests/test_support.h"
#include "util/error.h"

namespace sdfbench {
namespace {

namespace fs = std::filesystem;
using Bytes = std::vector<std::byte>;

sdf::MeshGridParams small_grid() {
  sdf::MeshGridParams p;
  p.cells_per_extent = 8;
  return p;
}

sdf::SceneHashParams small_hash() {
  sdf::SceneHashParams p;
  p.hash_cell = 20.0f;
  p.octree_depth = 2;
  return p;
}

Bytes read_all(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  const std::string text = s.str();
  Bytes bytes(text.size());
  std::memcpy(bytes.data(), text.data(), text.size());
  return bytes;
}

void write_all(const fs::path& path, const Bytes& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

template <class T>
void poke(Bytes& bytes, size_t offset, T value) {
  std::memcpy(bytes.data() + offset, &value, sizeof value);
}
template <class T>
T peek(const Bytes& bytes, size_t offset) {
  T value;
  std::memcpy(&value, bytes.data() + offset, sizeof value);
  return value;
}

// The v3 section table: after the 48-byte header, 40-byte entries
// {kind, codec version, index, owner, element size, pad, offset, count}.
constexpr size_t kTable = 48, kEntry = 40;
constexpr size_t kKind = 0, kVersion = 4, kIndex = 8, kOwner = 12, kElementBytes = 16, kOffset = 24, kCount = 32;

// The table position of every section of `contents` named `prefix`..., in table order.
std::vector<size_t> entries_named(const sdf::SdfCacheContents& contents, const std::string& prefix) {
  std::vector<size_t> out;
  for (size_t i = 0; i < contents.sections.size(); ++i)
    if (contents.sections[i].name.rfind(prefix, 0) == 0) out.push_back(kTable + i * kEntry);
  return out;
}

// The section of `contents` called `name` ("mesh 0 cell_triangles").
sdf::SdfCacheSection section_named(const sdf::SdfCacheContents& contents, const std::string& name) {
  for (const sdf::SdfCacheSection& s : contents.sections)
    if (s.name == name) return s;
  throw std::logic_error("no section " + name);
}

// The table position of every section of codec `kind` in a cache file.
std::vector<size_t> entries_of_kind(const Bytes& bytes, uint32_t kind) {
  std::vector<size_t> out;
  const uint32_t sections = peek<uint32_t>(bytes, 40);
  for (size_t i = 0; i < sections; ++i)
    if (peek<uint32_t>(bytes, kTable + i * kEntry + kKind) == kind) out.push_back(kTable + i * kEntry);
  return out;
}

// The requests for these structures' parameters (brick fields, global field).
template <class... Params>
sdf::StructureRequests requests(const Params&... params) {
  return {sdf::structure_request(params)...};
}

template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

class SdfCacheTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scene_ = new Scene(load_scene("thesis:sphere:10"));
    sdf_ = new sdf::SceneSdf(sdf::build_scene_sdf(*scene_, small_grid(), small_hash()));
  }
  static void TearDownTestSuite() {
    delete sdf_;
    delete scene_;
  }
  fs::path write_valid() const {
    const fs::path path = dir_.path() / "valid.sdfcache";
    sdf::write_sdf_cache(path, *scene_, *sdf_, small_grid());
    return path;
  }
  // `bytes` must be refused by every loader with a message containing `expected`.
  void expect_refused_everywhere(const Bytes& bytes, const std::string& expected) const {
    const fs::path path = dir_.path() / "bad.sdfcache";
    write_all(path, bytes);
    try {
      sdf::decode_sdf_cache(bytes, path.string());
      ADD_FAILURE() << "decode accepted a bad cache (" << expected << ")";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
    EXPECT_THROW(sdf::load_sdf_cache(path, *scene_, small_grid(), small_hash()), Error);
    std::ostringstream log;
    EXPECT_THROW(sdf::obtain_scene_sdf(*scene_, small_grid(), small_hash(), {path.string(), sdf::BadCachePolicy::Refuse}, log),
                 Error);
    const test::CommandResult inspect = test::run_sdfbench("inspect " + path.string());
    EXPECT_EQ(inspect.exit_code, 1) << inspect.output;
    EXPECT_NE(inspect.output.find(expected), std::string::npos) << inspect.output;
  }

  static Scene* scene_;
  static sdf::SceneSdf* sdf_;
  test::TempDir dir_;
};
Scene* SdfCacheTest::scene_ = nullptr;
sdf::SceneSdf* SdfCacheTest::sdf_ = nullptr;

TEST_F(SdfCacheTest, RoundTripIsBitIdentical) {
  const fs::path path = write_valid();
  const sdf::SceneSdf loaded = sdf::load_sdf_cache(path, *scene_, small_grid(), small_hash());
  ASSERT_EQ(loaded.mesh_grids.size(), sdf_->mesh_grids.size());
  test::expect_same_grid(sdf_->mesh_grids[0], loaded.mesh_grids[0]);
  const sdf::SceneHash& h = sdf_->hash;
  const sdf::SceneHash& g = loaded.hash;
  EXPECT_EQ(h.origin, g.origin);
  EXPECT_EQ(h.dims, g.dims);
  EXPECT_EQ(h.cell_root, g.cell_root);
  ASSERT_EQ(h.nodes.size(), g.nodes.size());
  EXPECT_EQ(0, std::memcmp(h.nodes.data(), g.nodes.data(), h.nodes.size() * sizeof(sdf::OctreeNode)));
  EXPECT_EQ(h.instance_lists, g.instance_lists);
  EXPECT_EQ(sdf_->world_to_object, loaded.world_to_object);
  // Writing what was loaded reproduces the file byte for byte.
  const fs::path again = dir_.path() / "again.sdfcache";
  sdf::write_sdf_cache(again, *scene_, loaded, small_grid());
  EXPECT_EQ(read_all(path), read_all(again));
  const test::CommandResult inspect = test::run_sdfbench("inspect " + path.string());
  EXPECT_EQ(inspect.exit_code, 0) << inspect.output;
  EXPECT_NE(inspect.output.find("--hash-cell 20 --octree-depth 2"), std::string::npos) << inspect.output;
}

TEST_F(SdfCacheTest, StaleSceneOrParametersAreRefused) {
  const fs::path path = write_valid();
  const Scene other = load_scene("thesis:sphere:10:2");  // same mesh, other seed: other transforms
  EXPECT_THROW(
      {
        try {
          sdf::load_sdf_cache(path, other, small_grid(), small_hash());
        } catch (const Error& e) {
          EXPECT_NE(std::string(e.what()).find("stale"), std::string::npos) << e.what();
          throw;
        }
      },
      Error);
  sdf::SceneHashParams deeper = small_hash();
  deeper.octree_depth = 3;
  EXPECT_THROW(sdf::load_sdf_cache(path, *scene_, small_grid(), deeper), Error);
  sdf::MeshGridParams finer = small_grid();
  finer.cells_per_extent = 9;
  EXPECT_THROW(sdf::load_sdf_cache(path, *scene_, finer, small_hash()), Error);
  // Materials do not change the structures: a recoloured scene still uses the cache.
  Scene recoloured = *scene_;
  recoloured.materials[0].albedo = glm::vec3(0.1f, 0.9f, 0.1f);
  EXPECT_NO_THROW(sdf::load_sdf_cache(path, recoloured, small_grid(), small_hash()));
}

TEST_F(SdfCacheTest, TruncatedFilesAreRefused) {
  const Bytes valid = read_all(write_valid());
  for (const size_t size : {size_t{0}, size_t{7}, size_t{60}, valid.size() / 2, valid.size() - 1})
    expect_refused_everywhere(Bytes(valid.begin(), valid.begin() + static_cast<std::ptrdiff_t>(size)),
                              size < 56 ? "too short" : "truncated");
}

TEST_F(SdfCacheTest, BitFlipsAreRefused) {
  const Bytes valid = read_all(write_valid());
  for (const size_t offset : {size_t{100}, valid.size() / 3, valid.size() - 20}) {
    Bytes flipped = valid;
    flipped[offset] ^= std::byte{0x10};
    expect_refused_everywhere(flipped, "checksum");
  }
}

TEST_F(SdfCacheTest, RandomBytesAreRefused) {
  Pcg32 rng(7);
  Bytes noise(4096);
  for (std::byte& b : noise) b = static_cast<std::byte>(rng.next() & 0xff);
  expect_refused_everywhere(noise, "not an sdfbench SDF cache");
}

// Hostile files with a correct checksum: the structural checks must catch each one.
TEST_F(SdfCacheTest, ResealedHostileFilesAreRefused) {
  const Bytes valid = read_all(write_valid());
  const sdf::SdfCacheContents c = sdf::decode_sdf_cache(valid, "valid");
  auto section = [&](const std::string& name) { return section_named(c, name); };
  struct Case {
    std::string name, expected;
    std::function<void(Bytes&)> mutate;
  };
  const std::vector<Case> cases = {
      {"section offset past the end", "outside the payload", [&](Bytes& b) { poke<uint64_t>(b, kTable + kOffset, b.size() * 2); }},
      {"section count past the end", "run past the end", [&](Bytes& b) { poke<uint64_t>(b, kTable + kCount, uint64_t{1} << 60); }},
      {"a required section of an unknown kind", "mesh grids: mesh grid params is missing",
       [&](Bytes& b) { poke<uint32_t>(b, kTable + kKind, 99u); }},
      {"a section index the codec does not have", "has unknown index", [&](Bytes& b) { poke<uint32_t>(b, kTable + kIndex, 99u); }},
      {"a per-file section with an owner", "has owner", [&](Bytes& b) { poke<uint32_t>(b, kTable + kOwner, 3u); }},
      {"an element size the codec does not use", "element size", [&](Bytes& b) { poke<uint32_t>(b, kTable + kElementBytes, 5u); }},
      {"a section twice (cell_triangles as a second cell_begin)", "mesh grids: mesh 0 cell_begin appears twice",
       [&](Bytes& b) { poke<uint32_t>(b, kTable + 3 * kEntry + kIndex, 2u); }},
      {"one structure in two codec versions", "in version 7 and 2", [&](Bytes& b) { poke<uint32_t>(b, kTable + kEntry + kVersion, 7u); }},
      {"the mesh grids in another codec version", "holds mesh grids in codec version 7; this sdfbench reads version 2",
       [&](Bytes& b) {
         for (const size_t e : entries_named(c, "mesh ")) poke<uint32_t>(b, e + kVersion, 7u);
       }},
      {"overlapping sections", "overlaps",
       [&](Bytes& b) { poke<uint64_t>(b, kTable + kEntry + kOffset, peek<uint64_t>(b, kTable + kOffset)); }},
      {"triangle index out of range", "triangle index",
       [&](Bytes& b) { poke<uint32_t>(b, section("mesh 0 cell_triangles").offset, 1000000u); }},
      {"child index out of range", "child index",
       [&](Bytes& b) { poke<int32_t>(b, section("octree nodes").offset, 1 << 30); }},
      {"child cycle", "child index", [&](Bytes& b) {
         const size_t last = section("octree nodes").offset + (section("octree nodes").count - 1) * 16;
         poke<int32_t>(b, last, 0);
       }},
      {"instance out of range", "names an instance",
       [&](Bytes& b) { poke<uint32_t>(b, section("instance lists").offset, 12345u); }},
      {"list out of range", "instance list out of range",
       [&](Bytes& b) { poke<uint32_t>(b, section("octree nodes").offset + 4, 0xfffffff0u); }},
      {"non-finite cell size", "grid", [&](Bytes& b) { poke<float>(b, section("mesh 0 grid header").offset + 12, NAN); }},
      {"cell_begin not monotone", "prefix sum",
       [&](Bytes& b) { poke<uint32_t>(b, section("mesh 0 cell_begin").offset + 8, 0xffffffffu); }},
      {"bad list rule", "list rule", [&](Bytes& b) { poke<uint32_t>(b, section("hash params").offset + 16, 7u); }},
      {"bad mesh grid rule", "mesh grid rule", [&](Bytes& b) { poke<uint32_t>(b, section("mesh grid params").offset + 12, 9u); }},
      {"wrong version", "format version", [&](Bytes& b) { poke<uint32_t>(b, 8, 99u); }},
      {"a version 2 cache (parameters in the header)",
       "format version 2; this sdfbench reads version 3 (written by an older sdfbench; rebuild it with `sdfbench build --cache`, "
       "or delete it)",
       [&](Bytes& b) { poke<uint32_t>(b, 8, 2u); }},
  };
  for (const Case& k : cases) {
    SCOPED_TRACE(k.name);
    Bytes hostile = valid;
    k.mutate(hostile);
    sdf::reseal_sdf_cache(hostile);
    expect_refused_everywhere(hostile, k.expected);
  }
  // A value that decodes but is not what the scene and the parameters give: refused on loading
  // for a scene (the decoder alone cannot know).
  Bytes halved = valid;
  const size_t at = section("mesh 0 grid header").offset + 12;
  poke<float>(halved, at, 0.5f * peek<float>(halved, at));
  sdf::reseal_sdf_cache(halved);
  const fs::path path = dir_.path() / "halved.sdfcache";
  write_all(path, halved);
  try {
    sdf::load_sdf_cache(path, *scene_, small_grid(), small_hash());
    ADD_FAILURE() << "a resealed grid with half the cell size was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("disagrees with itself: mesh '" + scene_->meshes[0].name + "''s grid has another cell size"),
              std::string::npos)
        << e.what();
  }
}

// A scaled grid (a mesh over kScaledGridFromTriangles: far cells hold bounds, not lists) in the
// cache: a bit-identical round trip, --fixed-grid a parameter it is stale for, and far-cell
// sections that lie refused (a non-finite bound, a far cell with a list, an upper bound below
// the bound, a count that is not the grid's).
TEST_F(SdfCacheTest, ScaledGridsRoundTripAndLyingFarCellsAreRefused) {
  Scene plane;  // 68 x 68 quads, 9248 triangles, wavy so that its cells differ
  plane.meshes.emplace_back();
  Mesh& mesh = plane.meshes[0];
  mesh.name = "plane";
  const uint32_t n = 68;
  for (uint32_t y = 0; y <= n; ++y)
    for (uint32_t x = 0; x <= n; ++x)
      mesh.positions.emplace_back(float(x) / n, float(y) / n, 0.05f * std::sin(0.4f * float(x + 2 * y)));
  for (uint32_t y = 0; y < n; ++y)
    for (uint32_t x = 0; x < n; ++x) {
      const uint32_t i = y * (n + 1) + x;
      mesh.triangles.emplace_back(i, i + 1, i + n + 2);
      mesh.triangles.emplace_back(i, i + n + 2, i + n + 1);
    }
  finish_mesh(mesh);
  plane.instances.push_back(Instance{});
  const sdf::MeshGridParams params;
  ASSERT_TRUE(sdf::has_far_cells(params, mesh.triangles.size()));
  const sdf::SceneSdf built = sdf::build_scene_sdf(plane, params, small_hash());
  ASSERT_GT(built.mesh_grids[0].far_cell_count(), 0u);
  const fs::path path = dir_.path() / "scaled.sdfcache";
  sdf::write_sdf_cache(path, plane, built, params);
  test::expect_same_grid(sdf::load_sdf_cache(path, plane, params, small_hash()).mesh_grids.at(0), built.mesh_grids[0]);
  sdf::MeshGridParams fixed = params;
  fixed.scale_with_triangles = false;
  EXPECT_NE(error_of([&] { sdf::load_sdf_cache(path, plane, fixed, small_hash()); }).find("is stale: built with mesh grid"),
            std::string::npos);

  const Bytes valid = read_all(path);
  const sdf::SdfCacheContents c = sdf::decode_sdf_cache(valid, "valid");
  auto section = [&](const std::string& name) { return section_named(c, name); };
  const sdf::MeshDistanceGrid& g = built.mesh_grids[0];
  size_t far = 0, listed = 0;
  while (!g.is_far(far)) ++far;
  while (g.cell_begin[listed] == g.cell_begin[listed + 1]) ++listed;
  const size_t distance = section("mesh 0 far distance").offset, upper = section("mesh 0 far upper").offset;
  const std::vector<std::pair<std::string, std::function<void(Bytes&)>>> cases = {
      {"a non-finite far-cell bound", [&](Bytes& b) { poke<float>(b, distance + 4 * far, NAN); }},
      {"has a list, or an upper bound below its bound", [&](Bytes& b) { poke<float>(b, distance + 4 * listed, 0.5f); }},
      {"has a list, or an upper bound below its bound",
       [&](Bytes& b) { poke<float>(b, upper + 4 * far, 0.5f * std::abs(peek<float>(b, distance + 4 * far))); }},
      {"far-cell bounds for", [&](Bytes& b) {
         for (const size_t e : entries_named(c, "mesh 0 far upper")) poke<uint64_t>(b, e + kCount, 1u);
       }},
  };
  for (const auto& [expected, mutate] : cases) {
    SCOPED_TRACE(expected);
    Bytes hostile = valid;
    mutate(hostile);
    sdf::reseal_sdf_cache(hostile);
    EXPECT_NE(error_of([&] { sdf::decode_sdf_cache(hostile, "hostile"); }).find(expected), std::string::npos);
  }
}

// sdf-bricks' brick fields ride in the same file: a bit-identical round trip, a cache without
// them (or with other parameters) stale for sdf-bricks but still good for the exact backends,
// and hostile brick sections refused.
TEST_F(SdfCacheTest, BrickFieldsRoundTripAndAreChecked) {
  const sdf::BrickFieldParams bricks{16, 3, sdf::SdfFormat::f16};
  sdf::SceneSdf with = sdf::build_scene_sdf(*scene_, small_grid(), small_hash(), requests(bricks));
  ASSERT_EQ(with.get<sdf::BrickFields>().fields.size(), scene_->meshes.size());
  const fs::path path = dir_.path() / "bricks.sdfcache";
  sdf::write_sdf_cache(path, *scene_, with, small_grid());
  const sdf::SceneSdf loaded = sdf::load_sdf_cache(path, *scene_, small_grid(), small_hash(), requests(bricks));
  ASSERT_EQ(loaded.get<sdf::BrickFields>().fields.size(), 1u);
  const sdf::BrickField &a = with.get<sdf::BrickFields>().fields[0], &b = loaded.get<sdf::BrickFields>().fields[0];
  EXPECT_EQ(a.origin, b.origin);
  EXPECT_EQ(a.voxel, b.voxel);
  EXPECT_EQ(a.bricks, b.bricks);
  EXPECT_EQ(a.band, b.band);
  EXPECT_EQ(a.quantization, b.quantization);
  EXPECT_EQ(a.indirection, b.indirection);
  EXPECT_EQ(a.atlas, b.atlas);
  EXPECT_EQ(a.coarse, b.coarse);
  const fs::path again = dir_.path() / "bricks-again.sdfcache";
  sdf::write_sdf_cache(again, *scene_, loaded, small_grid());
  EXPECT_EQ(read_all(path), read_all(again));
  EXPECT_NO_THROW(sdf::load_sdf_cache(path, *scene_, small_grid(), small_hash()));  // the exact backends ignore them
  const sdf::BrickFieldParams other{16, 3, sdf::SdfFormat::u8};
  try {
    sdf::load_sdf_cache(path, *scene_, small_grid(), small_hash(), requests(other));
    ADD_FAILURE() << "a cache with other brick parameters was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--sdf-format f16, requested"), std::string::npos) << e.what();
  }
  try {
    sdf::load_sdf_cache(write_valid(), *scene_, small_grid(), small_hash(), requests(bricks));
    ADD_FAILURE() << "a cache without brick fields was accepted for sdf-bricks";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("holds no brick fields"), std::string::npos) << e.what();
  }
  // obtain_scene_sdf completes such a cache (exact structures loaded, brick fields added and
  // written back), and refuses one with other brick parameters under the default policy.
  std::ostringstream log;
  const fs::path plain = write_valid();
  const sdf::SceneSdf completed =
      sdf::obtain_scene_sdf(*scene_, small_grid(), small_hash(), {plain.string(), sdf::BadCachePolicy::Refuse}, log, requests(bricks));
  EXPECT_EQ(completed.get<sdf::BrickFields>().fields.size(), 1u);
  EXPECT_NE(log.str().find("added brick fields"), std::string::npos) << log.str();
  EXPECT_NO_THROW(sdf::load_sdf_cache(plain, *scene_, small_grid(), small_hash(), requests(bricks)));
  EXPECT_THROW(
      sdf::obtain_scene_sdf(*scene_, small_grid(), small_hash(), {plain.string(), sdf::BadCachePolicy::Refuse}, log, requests(other)),
      Error);
  const Bytes valid = read_all(path);
  const sdf::SdfCacheContents c = sdf::decode_sdf_cache(valid, "valid");
  auto section = [&](const std::string& name) { return section_named(c, name); };
  const struct {
    const char* name;
    const char* expected;
    std::function<void(Bytes&)> mutate;
  } cases[] = {
      {"atlas index out of range", "atlas index is out of range",
       [&](Bytes& b) {
         const auto s = section("mesh 0 brick indirection");
         for (uint64_t i = 0; i < s.count; ++i)
           if (peek<uint32_t>(b, s.offset + 4 * i) != sdf::kEmptyBrick) return poke<uint32_t>(b, s.offset + 4 * i, 0x7fffffffu);
       }},
      {"a value beyond the band", "beyond the band",
       [&](Bytes& b) { poke<uint16_t>(b, section("mesh 0 brick atlas").offset, 0x7c00u); }},  // +inf in f16
      {"non-finite coarse value", "coarse", [&](Bytes& b) { poke<float>(b, section("mesh 0 brick coarse level").offset, NAN); }},
      {"more stored bricks than bricks", "stored bricks",
       [&](Bytes& b) { poke<uint32_t>(b, section("mesh 0 brick header").offset + 28, 0xffffffffu); }},
      {"bad brick parameters", "brick field parameters", [&](Bytes& b) { poke<uint32_t>(b, section("brick params").offset, 2u); }},
      {"a bad format", "brick field parameters", [&](Bytes& b) { poke<uint32_t>(b, section("brick params").offset + 8, 3u); }},
  };
  for (const auto& k : cases) {
    SCOPED_TRACE(k.name);
    Bytes hostile = valid;
    k.mutate(hostile);
    sdf::reseal_sdf_cache(hostile);
    try {
      sdf::decode_sdf_cache(hostile, "hostile");
      ADD_FAILURE() << "decode accepted it";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(k.expected), std::string::npos) << e.what();
    }
  }
}

// Each structure's sections carry their codec's version: a copy in another version is stale for
// that structure alone (the exact backends still load the cache; sdf-bricks refuses it, or
// rebuilds it when asked), and a structure of a kind this sdfbench does not know is skipped (the
// cache lacks it and is completed).
TEST_F(SdfCacheTest, AStructureInAnotherCodecVersionIsStaleForItAlone) {
  const sdf::BrickFieldParams bricks{16, 3, sdf::SdfFormat::f16};
  const sdf::SectionCodec& codec = *sdf::codec_of_kind(sdf::BrickFields::kKind);
  const fs::path path = dir_.path() / "bricks.sdfcache";
  sdf::write_sdf_cache(path, *scene_, sdf::build_scene_sdf(*scene_, small_grid(), small_hash(), requests(bricks)), small_grid());
  const Bytes valid = read_all(path);
  ASSERT_FALSE(entries_of_kind(valid, codec.kind).empty());

  Bytes newer = valid;
  for (const size_t e : entries_of_kind(valid, codec.kind)) poke<uint32_t>(newer, e + kVersion, codec.version + 1);
  sdf::reseal_sdf_cache(newer);
  write_all(path, newer);
  const sdf::SdfCacheContents c = sdf::decode_sdf_cache(newer, "newer");
  EXPECT_FALSE(c.sdf.holds(sdf::BrickFields::kKind));
  ASSERT_EQ(c.structures.size(), 3u);
  EXPECT_EQ(c.structures[2].name, "brick fields");
  EXPECT_FALSE(c.structures[2].read);
  EXPECT_NO_THROW(sdf::load_sdf_cache(path, *scene_, small_grid(), small_hash()));
  const std::string stale = error_of([&] { sdf::load_sdf_cache(path, *scene_, small_grid(), small_hash(), requests(bricks)); });
  EXPECT_NE(stale.find("is stale: it holds brick fields in codec version " + std::to_string(codec.version + 1) +
                       ", this sdfbench reads version " + std::to_string(codec.version)),
            std::string::npos)
      << stale;
  std::ostringstream log;
  const std::string refused = error_of([&] {
    sdf::obtain_scene_sdf(*scene_, small_grid(), small_hash(), {path.string(), sdf::BadCachePolicy::Refuse}, log, requests(bricks));
  });
  EXPECT_NE(refused.find("codec version"), std::string::npos) << refused;
  EXPECT_NE(refused.find("pass --on-bad-cache rebuild to replace it"), std::string::npos) << refused;
  const test::CommandResult inspect = test::run_sdfbench("inspect " + path.string());
  EXPECT_EQ(inspect.exit_code, 0) << inspect.output;
  EXPECT_NE(inspect.output.find("brick fields v" + std::to_string(codec.version + 1) + " (not read)"), std::string::npos)
      << inspect.output;
  sdf::obtain_scene_sdf(*scene_, small_grid(), small_hash(), {path.string(), sdf::BadCachePolicy::Rebuild}, log, requests(bricks));
  EXPECT_NE(log.str().find("rebuilding"), std::string::npos) << log.str();
  EXPECT_NO_THROW(sdf::load_sdf_cache(path, *scene_, small_grid(), small_hash(), requests(bricks)));

  Bytes unknown = valid;
  for (const size_t e : entries_of_kind(valid, codec.kind)) poke<uint32_t>(unknown, e + kKind, 77u);
  sdf::reseal_sdf_cache(unknown);
  write_all(path, unknown);
  EXPECT_EQ(sdf::decode_sdf_cache(unknown, "unknown").structures.at(2).name, "kind 77");
  EXPECT_NE(error_of([&] { sdf::load_sdf_cache(path, *scene_, small_grid(), small_hash(), requests(bricks)); }).find("holds no brick fields"),
            std::string::npos);
  log.str("");
  sdf::obtain_scene_sdf(*scene_, small_grid(), small_hash(), {path.string(), sdf::BadCachePolicy::Refuse}, log, requests(bricks));
  EXPECT_NE(log.str().find("added brick fields"), std::string::npos) << log.str();
  EXPECT_NO_THROW(sdf::load_sdf_cache(path, *scene_, small_grid(), small_hash(), requests(bricks)));
}

// A cache of format version 2 (build parameters in the header, before the per-structure codecs)
// is refused as another version with how to replace it, and rebuilt when asked.
TEST_F(SdfCacheTest, AVersion2CacheSaysHowToRebuildIt) {
  const fs::path path = write_valid();
  Bytes old = read_all(path);
  poke<uint32_t>(old, 8, 2u);
  sdf::reseal_sdf_cache(old);
  write_all(path, old);
  std::ostringstream log;
  const std::string refused = error_of([&] {
    sdf::obtain_scene_sdf(*scene_, small_grid(), small_hash(), {path.string(), sdf::BadCachePolicy::Refuse}, log);
  });
  for (const char* words : {"has format version 2; this sdfbench reads version 3", "written by an older sdfbench",
                            "rebuild it with `sdfbench build --cache`", "pass --on-bad-cache rebuild to replace it"})
    EXPECT_NE(refused.find(words), std::string::npos) << refused;
  const test::CommandResult render = test::run_sdfbench("render --scene thesis:sphere:10 --backend sdf-cpu --size 16x9 --frames 1 "
                                                        "--warmup 0 --cells-per-extent 8 --hash-cell 20 --octree-depth 2 --cache " +
                                                        path.string());
  EXPECT_EQ(render.exit_code, 1) << render.output;
  EXPECT_NE(render.output.find("format version 2"), std::string::npos) << render.output;
  EXPECT_NE(render.output.find("--on-bad-cache rebuild"), std::string::npos) << render.output;
  sdf::obtain_scene_sdf(*scene_, small_grid(), small_hash(), {path.string(), sdf::BadCachePolicy::Rebuild}, log);
  EXPECT_NE(log.str().find("format version 2"), std::string::npos) << log.str();
  EXPECT_NE(log.str().find("rebuilding"), std::string::npos) << log.str();
  EXPECT_NO_THROW(sdf::load_sdf_cache(path, *scene_, small_grid(), small_hash()));
}

// A coarse global field (about 3 voxels per object, f16): a few hundred bricks, built in milliseconds.
sdf::GlobalFieldParams small_global(const Scene& scene) {
  const glm::vec3 extent = scene.world_bounds(scene.instances[0]).extent();
  sdf::GlobalFieldParams global;
  global.voxel = std::max({extent.x, extent.y, extent.z}) / 3.0f;
  global.band = 2;
  global.format = sdf::SdfFormat::f16;
  return global;
}

// sdf-global's global field rides in the same file: a round trip equal in every field, a cache
// without it completed (and written back), one with other parameters stale for sdf-global but
// still good for the other backends.
TEST_F(SdfCacheTest, GlobalFieldRoundTripsAndIsCompleted) {
  const sdf::GlobalFieldParams global = small_global(*scene_);
  const sdf::SceneSdf with = sdf::build_scene_sdf(*scene_, small_grid(), small_hash(), requests(global));
  ASSERT_NE(with.find<sdf::GlobalFieldStructure>(), nullptr);
  ASSERT_GT(with.get<sdf::GlobalFieldStructure>().field.field.stored_bricks(), 0u);
  ASSERT_FALSE(with.get<sdf::GlobalFieldStructure>().field.list_instances.empty());
  const fs::path path = dir_.path() / "global.sdfcache";
  sdf::write_sdf_cache(path, *scene_, with, small_grid());
  const sdf::SceneSdf loaded = sdf::load_sdf_cache(path, *scene_, small_grid(), small_hash(), requests(global));
  ASSERT_NE(loaded.find<sdf::GlobalFieldStructure>(), nullptr);
  EXPECT_TRUE(sdf::same(loaded.get<sdf::GlobalFieldStructure>().params, global));
  EXPECT_EQ(loaded.get<sdf::GlobalFieldStructure>().params.voxel, global.voxel);
  const sdf::GlobalField &a = with.get<sdf::GlobalFieldStructure>().field, &b = loaded.get<sdf::GlobalFieldStructure>().field;
  EXPECT_EQ(a.field.origin, b.field.origin);
  EXPECT_EQ(a.field.voxel, b.field.voxel);
  EXPECT_EQ(a.field.bricks, b.field.bricks);
  EXPECT_EQ(a.field.format, b.field.format);
  EXPECT_EQ(a.field.band, b.field.band);
  EXPECT_EQ(a.field.quantization, b.field.quantization);
  EXPECT_EQ(a.field.indirection, b.field.indirection);
  EXPECT_EQ(a.field.atlas, b.field.atlas);
  EXPECT_EQ(a.field.coarse, b.field.coarse);
  EXPECT_EQ(a.field.build_ms, b.field.build_ms);
  EXPECT_EQ(a.voxel_request, b.voxel_request);
  EXPECT_EQ(a.list_begin, b.list_begin);
  EXPECT_EQ(a.list_instances, b.list_instances);
  EXPECT_EQ(a.build_ms, b.build_ms);
  EXPECT_FALSE(loaded.holds(sdf::BrickFields::kKind));
  const fs::path again = dir_.path() / "global-again.sdfcache";
  sdf::write_sdf_cache(again, *scene_, loaded, small_grid());
  EXPECT_EQ(read_all(path), read_all(again));
  EXPECT_NO_THROW(sdf::load_sdf_cache(path, *scene_, small_grid(), small_hash()));  // the other backends ignore it
  const test::CommandResult inspect = test::run_sdfbench("inspect " + path.string());
  EXPECT_EQ(inspect.exit_code, 0) << inspect.output;
  EXPECT_NE(inspect.output.find("global field --global-voxel"), std::string::npos) << inspect.output;
  EXPECT_NE(inspect.output.find("global list instances"), std::string::npos) << inspect.output;

  // A field whose voxel was changed and the file resealed decodes, but is not what its request gives.
  {
    const sdf::SdfCacheContents contents = sdf::decode_sdf_cache(read_all(path), "global");
    Bytes edited = read_all(path);
    for (const sdf::SdfCacheSection& section : contents.sections)
      if (section.name == "global header") poke<float>(edited, section.offset + 12, 2.0f * a.field.voxel);
    sdf::reseal_sdf_cache(edited);
    const fs::path resealed = dir_.path() / "resealed.sdfcache";
    write_all(resealed, edited);
    try {
      sdf::load_sdf_cache(resealed, *scene_, small_grid(), small_hash(), requests(global));
      ADD_FAILURE() << "a resealed global field with another voxel was accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("its global field's voxel is not the one its request"), std::string::npos) << e.what();
    }
  }
  sdf::GlobalFieldParams other = global;
  other.format = sdf::SdfFormat::u8;
  try {
    sdf::load_sdf_cache(path, *scene_, small_grid(), small_hash(), requests(other));
    ADD_FAILURE() << "a cache with other global field parameters was accepted";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("stale"), std::string::npos) << message;
    EXPECT_NE(message.find(sdf::describe(global) + ", requested " + sdf::describe(other)), std::string::npos) << message;
  }
  try {
    sdf::load_sdf_cache(write_valid(), *scene_, small_grid(), small_hash(), requests(global));
    ADD_FAILURE() << "a cache without a global field was accepted for sdf-global";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("holds no global field"), std::string::npos) << e.what();
  }

  // obtain_scene_sdf completes a cache without it (the same field as a fresh build), refuses one
  // with other parameters under the default policy and rebuilds it when asked.
  std::ostringstream log;
  const fs::path plain = write_valid();
  const sdf::SceneSdf completed = sdf::obtain_scene_sdf(*scene_, small_grid(), small_hash(),
                                                        {plain.string(), sdf::BadCachePolicy::Refuse}, log, requests(global));
  ASSERT_NE(completed.find<sdf::GlobalFieldStructure>(), nullptr);
  EXPECT_EQ(completed.get<sdf::GlobalFieldStructure>().field.field.atlas, a.field.atlas);
  EXPECT_EQ(completed.get<sdf::GlobalFieldStructure>().field.list_instances, a.list_instances);
  EXPECT_NE(log.str().find("SDF cache: added the global field (" + sdf::describe(global) + ") to '" + plain.string() + "'"),
            std::string::npos)
      << log.str();
  EXPECT_NO_THROW(sdf::load_sdf_cache(plain, *scene_, small_grid(), small_hash(), requests(global)));
  log.str("");
  sdf::obtain_scene_sdf(*scene_, small_grid(), small_hash(), {plain.string(), sdf::BadCachePolicy::Refuse}, log, requests(global));
  EXPECT_NE(log.str().find("build skipped"), std::string::npos) << log.str();
  EXPECT_EQ(log.str().find("added"), std::string::npos) << log.str();
  EXPECT_THROW(sdf::obtain_scene_sdf(*scene_, small_grid(), small_hash(), {plain.string(), sdf::BadCachePolicy::Refuse}, log,
                                     requests(other)),
               Error);
  log.str("");
  sdf::obtain_scene_sdf(*scene_, small_grid(), small_hash(), {plain.string(), sdf::BadCachePolicy::Rebuild}, log, requests(other));
  EXPECT_NE(log.str().find("rebuilding"), std::string::npos) << log.str();
  EXPECT_NO_THROW(sdf::load_sdf_cache(plain, *scene_, small_grid(), small_hash(), requests(other)));
  // Brick fields and the global field together: both completed in one pass.
  const sdf::BrickFieldParams bricks{16, 3, sdf::SdfFormat::f32};
  const fs::path both = write_valid();
  log.str("");
  sdf::obtain_scene_sdf(*scene_, small_grid(), small_hash(), {both.string(), sdf::BadCachePolicy::Refuse}, log, requests(bricks, global));
  EXPECT_NE(log.str().find("added brick fields"), std::string::npos) << log.str();
  EXPECT_NE(log.str().find("added the global field"), std::string::npos) << log.str();
  EXPECT_NO_THROW(sdf::load_sdf_cache(both, *scene_, small_grid(), small_hash(), requests(bricks, global)));
}

// Hostile global sections and parameters, re-checksummed: each refused with a clear message by
// every loader (never a crash); f16 values that round just past the band, as the build stores
// them, still accepted.
TEST_F(SdfCacheTest, HostileGlobalFieldsAreRefused) {
  const sdf::GlobalFieldParams global = small_global(*scene_);
  const fs::path path = dir_.path() / "global.sdfcache";
  sdf::write_sdf_cache(path, *scene_, sdf::build_scene_sdf(*scene_, small_grid(), small_hash(), requests(global)), small_grid());

  // A clamped f16 value rounds to the nearest half, past the band by up to its quantization
  // (band / 2048): accepted; a value farther out: refused.
  const Bytes valid = read_all(path);
  const sdf::SdfCacheContents c = sdf::decode_sdf_cache(valid, "valid");
  {
    sdf::SdfCacheContents edge = c;
    sdf::GlobalFieldStructure global = c.sdf.get<sdf::GlobalFieldStructure>();  // a copy to edit (held ones are shared)
    const float band = global.field.field.band, quantization = global.field.field.quantization;
    const auto with_first_sample = [&](uint16_t h) {
      std::memcpy(global.field.field.atlas.data(), &h, sizeof h);
      edge.sdf.set(global);
      return sdf::encode_sdf_cache(edge);
    };
    for (const float v : {band, -band, band + 0.9f * quantization}) {
      const uint16_t h = glm::packHalf1x16(v);
      if (std::abs(glm::unpackHalf1x16(h)) > band + quantization) continue;  // not a value the build can store
      EXPECT_NO_THROW(sdf::decode_sdf_cache(with_first_sample(h), "edge")) << v << " for band " << band;
    }
    EXPECT_LE(std::abs(glm::unpackHalf1x16(glm::packHalf1x16(band))), band + quantization);
    EXPECT_THROW(sdf::decode_sdf_cache(with_first_sample(glm::packHalf1x16(-band * 1.01f)), "beyond"), Error);
  }
  auto section = [&](const std::string& name) { return section_named(c, name); };
  const auto first_stored = [&](const Bytes& b) -> uint64_t {
    const auto s = section("global indirection");
    for (uint64_t i = 0; i < s.count; ++i)
      if (peek<uint32_t>(b, s.offset + 4 * i) != sdf::kEmptyBrick) return s.offset + 4 * i;
    throw std::logic_error("no stored brick");
  };
  const struct {
    const char* name;
    const char* expected;
    std::function<void(Bytes&)> mutate;
  } cases[] = {
      {"list entry names no instance", "a brick list names an instance >= 10",
       [&](Bytes& b) { poke<uint32_t>(b, section("global list instances").offset, 10u); }},
      {"indirection entry out of range", "global field: a brick's atlas index is out of range",
       [&](Bytes& b) { poke<uint32_t>(b, first_stored(b), 0x7fffffffu); }},
      {"empty brick made stored past the end", "atlas index is out of range",
       [&](Bytes& b) {
         const auto s = section("global indirection");
         for (uint64_t i = 0; i < s.count; ++i)
           if (peek<uint32_t>(b, s.offset + 4 * i) == sdf::kEmptyBrick)
             return poke<uint32_t>(b, s.offset + 4 * i, static_cast<uint32_t>(section("global list begin").count - 1));
       }},
      {"list_begin not monotone", "global field: list begin is not a valid prefix sum",
       [&](Bytes& b) { poke<uint32_t>(b, section("global list begin").offset + 4, 0xffffffffu); }},
      {"list_begin not starting at 0", "list begin is not a valid prefix sum",
       [&](Bytes& b) { poke<uint32_t>(b, section("global list begin").offset, 1u); }},
      {"list_begin not ending at the list size", "list begin is not a valid prefix sum",
       [&](Bytes& b) {
         const auto s = section("global list begin");
         poke<uint32_t>(b, s.offset + 4 * (s.count - 1), peek<uint32_t>(b, s.offset + 4 * (s.count - 1)) - 1);
       }},
      {"list entry count differs from the header", "list instances, header says",
       [&](Bytes& b) { poke<uint32_t>(b, section("global header").offset + 32, 12345u); }},
      {"more stored bricks than bricks", "global field: more stored bricks than bricks",
       [&](Bytes& b) { poke<uint32_t>(b, section("global header").offset + 28, 0xffffffffu); }},
      {"too many bricks", "global field: bad dimensions",
       [&](Bytes& b) { poke<uint32_t>(b, section("global header").offset + 16, 0x40000000u); }},
      {"non-finite voxel", "global field: origin or voxel not finite",
       [&](Bytes& b) { poke<float>(b, section("global header").offset + 12, NAN); }},
      {"a value beyond the band", "global field: an atlas value is not finite or lies beyond the band",
       [&](Bytes& b) { poke<uint16_t>(b, section("global atlas").offset, 0x7c00u); }},  // +inf in f16
      {"negative coarse value", "global field: a coarse value is not finite or negative",
       [&](Bytes& b) { poke<float>(b, section("global coarse level").offset, -1.0f); }},
      {"non-finite coarse value", "coarse value is not finite",
       [&](Bytes& b) { poke<float>(b, section("global coarse level").offset + 4, NAN); }},
      {"bad band", "global field parameters", [&](Bytes& b) { poke<uint32_t>(b, section("global params").offset + 4, 0u); }},
      {"bad format", "global field parameters", [&](Bytes& b) { poke<uint32_t>(b, section("global params").offset + 8, 9u); }},
      {"non-finite voxel request", "global field parameters",
       [&](Bytes& b) { poke<float>(b, section("global params").offset, NAN); }},
      {"a global section missing", "global field: global list instances is missing",
       [&](Bytes& b) { poke<uint32_t>(b, entries_named(c, "global list instances").at(0) + kKind, 99u); }},
  };
  for (const auto& k : cases) {
    SCOPED_TRACE(k.name);
    Bytes hostile = valid;
    k.mutate(hostile);
    sdf::reseal_sdf_cache(hostile);
    expect_refused_everywhere(hostile, k.expected);
  }
}

TEST_F(SdfCacheTest, ObtainLoadsBuildsOrRebuildsAsAsked) {
  const fs::path path = dir_.path() / "obtained.sdfcache";
  std::ostringstream log;
  const sdf::CacheOptions cache{path.string(), sdf::BadCachePolicy::Refuse};
  sdf::obtain_scene_sdf(*scene_, small_grid(), small_hash(), cache, log);
  EXPECT_NE(log.str().find("built and wrote"), std::string::npos) << log.str();
  log.str("");
  sdf::obtain_scene_sdf(*scene_, small_grid(), small_hash(), cache, log);
  EXPECT_NE(log.str().find("build skipped"), std::string::npos) << log.str();
  // Corrupt it: refused by default, rebuilt (and valid again) when asked.
  Bytes bytes = read_all(path);
  bytes.resize(bytes.size() / 2);
  write_all(path, bytes);
  EXPECT_THROW(sdf::obtain_scene_sdf(*scene_, small_grid(), small_hash(), cache, log), Error);
  log.str("");
  sdf::obtain_scene_sdf(*scene_, small_grid(), small_hash(), {path.string(), sdf::BadCachePolicy::Rebuild}, log);
  EXPECT_NE(log.str().find("rebuilding"), std::string::npos) << log.str();
  EXPECT_NO_THROW(sdf::load_sdf_cache(path, *scene_, small_grid(), small_hash()));
}

TEST_F(SdfCacheTest, CommandLineBuildWritesAndRenderRefusesCorruptCache) {
  const fs::path path = dir_.path() / "cli.sdfcache";
  const std::string structure = " --cells-per-extent 8 --hash-cell 20 --octree-depth 2";
  const test::CommandResult build = test::run_sdfbench("build --scene thesis:sphere:10" + structure + " --cache " + path.string());
  ASSERT_EQ(build.exit_code, 0) << build.output;
  const Bytes valid = read_all(path);
  for (const char* backend : {"sdf-cpu", "sdf-octree"}) {  // the CPU reference and the GPU upload path
    write_all(path, valid);
    const std::string render = std::string("render --scene thesis:sphere:10 --backend ") + backend + " --size 16x9" +
                               structure + " --cache " + path.string();
    const test::CommandResult loaded = test::run_sdfbench(render);
    EXPECT_EQ(loaded.exit_code, 0) << loaded.output;
    EXPECT_NE(loaded.output.find("build skipped"), std::string::npos) << loaded.output;
    Bytes bytes = valid;
    bytes[bytes.size() / 2] ^= std::byte{1};
    write_all(path, bytes);
    const test::CommandResult refused = test::run_sdfbench(render);
    EXPECT_EQ(refused.exit_code, 1) << refused.output;
    EXPECT_NE(refused.output.find("checksum"), std::string::npos) << refused.output;
    const test::CommandResult rebuilt = test::run_sdfbench(render + " --on-bad-cache rebuild");
    EXPECT_EQ(rebuilt.exit_code, 0) << rebuilt.output;
    EXPECT_NE(rebuilt.output.find("rebuilding"), std::string::npos) << rebuilt.output;
  }
  const test::CommandResult missing = test::run_sdfbench("inspect " + (dir_.path() / "nope").string());
  EXPECT_EQ(missing.exit_code, 1) << missing.output;
}

}  // namespace
}  // namespace sdfbench

namespace sdfbench {
namespace {

// This process' builds reused (build_reuse.h): the same geometry and parameters give the same
// structure as a fresh build, with the first build's time; another parameter or mesh builds anew.
TEST(SdfBuildReuse, SameInputsReuseAndOthersBuild) {
  ::unsetenv("SDFBENCH_BUILD_STORE");  // this process' builds alone (ctest sets the store)
  sdf::forget_reused_builds();
  const Scene scene = load_scene("thesis:teapot:3");
  const Mesh& mesh = scene.meshes.at(0);
  int builds = 0;
  const sdf::MeshGridParams params;
  const auto build = [&](const sdf::MeshGridParams& p) {
    return [&, p] {
      ++builds;
      return sdf::build_mesh_distance_grid(mesh, p);
    };
  };
  const sdf::MeshDistanceGrid first = sdf::reuse_mesh_grid(mesh, params, build(params));
  const sdf::MeshDistanceGrid again = sdf::reuse_mesh_grid(mesh, params, build(params));
  EXPECT_EQ(builds, 1);
  test::expect_same_grid(first, again);
  EXPECT_EQ(first.build_ms, again.build_ms);
  test::expect_same_grid(again, sdf::build_mesh_distance_grid(mesh, params));
  sdf::MeshGridParams finer = params;
  finer.cells_per_extent = 16;
  sdf::reuse_mesh_grid(mesh, finer, build(finer));
  sdf::MeshGridParams capped = params;
  capped.max_bytes = 1 << 20;  // a limit is part of the key: a reused build never bypasses it
  EXPECT_THROW(sdf::reuse_mesh_grid(mesh, capped, build(capped)), Error);
  capped.max_bytes = 64 << 20;
  sdf::reuse_mesh_grid(mesh, capped, build(capped));
  EXPECT_EQ(builds, 4);
  Mesh moved = mesh;
  moved.positions[0].x += 1e-3f;
  sdf::reuse_mesh_grid(moved, params, [&] {
    ++builds;
    return sdf::build_mesh_distance_grid(moved, params);
  });
  EXPECT_EQ(builds, 5);
  sdf::forget_reused_builds();
  sdf::reuse_mesh_grid(mesh, params, build(params));
  EXPECT_EQ(builds, 6);

  // The scene hash (sdf-octree's and sdf-bricks'): keyed by the geometry and its parameters.
  const sdf::SceneSdf sdf = sdf::build_scene_sdf(scene, params, sdf::SceneHashParams{});
  int hashes = 0;
  const auto hash_of = [&](const sdf::SceneHashParams& p) {
    return sdf::reuse_scene_hash(scene, params, p, [&] {
      ++hashes;
      return sdf::build_scene_hash(scene, sdf.mesh_grids, p);
    });
  };
  EXPECT_EQ(hash_of(sdf::SceneHashParams{}).instance_lists, sdf.hash.instance_lists);
  EXPECT_EQ(hashes, 0) << "build_scene_sdf's hash is reused";
  sdf::SceneHashParams hash_only;
  hash_only.octree_depth = 0;
  hash_of(hash_only);
  hash_of(hash_only);
  EXPECT_EQ(hashes, 1);

  // The optional structures, built by their requests: a reused one is the same (shared) entry.
  // The global field is keyed by the scene's geometry (an instance moved is another field).
  sdf::GlobalFieldParams global;
  global.voxel = 0.3f;
  const auto global_of = [&](const Scene& s) {
    return sdf::build_scene_sdf(s, params, sdf::SceneHashParams{}, requests(global)).optional.at(sdf::GlobalFieldStructure::kKind);
  };
  const auto a = global_of(scene), b = global_of(scene);
  EXPECT_EQ(a, b) << "the global field is reused";
  Scene shifted = scene;
  shifted.instances[0].transform.translation.x += 0.5f;
  EXPECT_NE(global_of(shifted), a);
  const auto& field_a = dynamic_cast<const sdf::GlobalFieldStructure&>(*a).field;
  EXPECT_EQ(field_a.field.atlas, sdf::build_global_field(scene, sdf, params, global).field.atlas) << "as a fresh build";
  global.max_bytes += 1 << 20;  // a limit is part of the key: a reused build never bypasses it
  EXPECT_NE(global_of(scene), a);
  // Brick fields are keyed by each mesh: another scene of the same mesh reuses them.
  const sdf::BrickFieldParams bricks{16, 3, sdf::SdfFormat::f16};
  const auto fields_of = [&](const Scene& s) {
    return sdf::build_scene_sdf(s, params, sdf::SceneHashParams{}, requests(bricks)).get<sdf::BrickFields>().fields.at(0);
  };
  const sdf::BrickField built = fields_of(scene), reused = fields_of(shifted);
  EXPECT_EQ(built.build_ms, reused.build_ms) << "the first build's time: reused";
  EXPECT_EQ(built.atlas, reused.atlas);
  EXPECT_EQ(built.atlas, sdf::build_brick_field(scene.meshes[0], sdf.mesh_grids[0], bricks).atlas) << "as a fresh build";
}

// The store on disk (build_store.h): what one process built, a later one loads (here: this
// process after forgetting its own builds) and it equals a fresh build; a damaged entry is built
// again and replaced; an unwritable store costs a build, nothing else; unset, nothing is written.
TEST(SdfBuildStore, ALaterProcessLoadsTheGridOneBuilt) {
  const test::TempDir dir;
  const Scene scene = load_scene("thesis:monkey:1");
  const Mesh& mesh = scene.meshes.at(0);
  const sdf::MeshGridParams params;
  int builds = 0;
  const auto grid = [&] {
    sdf::forget_reused_builds();  // as a new process
    return sdf::reuse_mesh_grid(mesh, params, [&] {
      ++builds;
      return sdf::build_mesh_distance_grid(mesh, params);
    });
  };
  ::unsetenv("SDFBENCH_BUILD_STORE");
  grid();
  EXPECT_TRUE(fs::is_empty(dir.path()));
  const fs::path store = dir.path() / "store";
  ::setenv("SDFBENCH_BUILD_STORE", store.c_str(), 1);
  const sdf::MeshDistanceGrid built = grid();
  EXPECT_EQ(builds, 2);
  std::vector<fs::path> entries;
  for (const auto& e : fs::recursive_directory_iterator(store))
    if (e.is_regular_file()) entries.push_back(e.path());
  ASSERT_EQ(entries.size(), 1u);
  EXPECT_EQ(entries[0].parent_path().filename().string().size(), 40u) << "a folder named by the build ID (SHA-1)";

  const sdf::MeshDistanceGrid loaded = grid();
  EXPECT_EQ(builds, 2);
  test::expect_same_grid(loaded, built);
  EXPECT_EQ(loaded.build_ms, built.build_ms);

  fs::resize_file(entries[0], fs::file_size(entries[0]) / 2);
  test::expect_same_grid(grid(), built);
  EXPECT_EQ(builds, 3);
  grid();
  EXPECT_EQ(builds, 3) << "the damaged entry was replaced";

  sdf::MeshGridParams other = params;  // other parameters: another entry
  other.cells_per_extent = 16;
  sdf::forget_reused_builds();
  sdf::reuse_mesh_grid(mesh, other, [&] {
    ++builds;
    return sdf::build_mesh_distance_grid(mesh, other);
  });
  EXPECT_EQ(builds, 4);

  const fs::path blocked = dir.write("blocked", "a file where the store's folder would be");
  ::setenv("SDFBENCH_BUILD_STORE", blocked.c_str(), 1);
  test::expect_same_grid(grid(), built);
  test::expect_same_grid(grid(), built);
  EXPECT_EQ(builds, 6);
  ::unsetenv("SDFBENCH_BUILD_STORE");
}

}  // namespace
}  // namespace sdfbench
