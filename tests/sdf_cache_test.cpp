// The SDF cache: a bit-identical round trip, and a clear Error (never a crash, never structures)
// for stale, truncated, bit-flipped, random and hostile (re-checksummed) files, from every
// loader: decode (inspect), load_sdf_cache, obtain_scene_sdf, and the CLI.
#include <gtest/gtest.h>

#include <cstring>
#include <functional>
#include <fstream>
#include <sstream>

#include "renderers/sdf/sdf_cache.h"
#include "renderers/sdf/sdf_cache_format.h"
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
                              size < 96 ? "too short" : "truncated");
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
  auto section = [&](const std::string& name) {
    for (const sdf::SdfCacheSection& s : c.sections)
      if (s.name == name) return s;
    throw std::logic_error("no section " + name);
  };
  constexpr size_t kTable = 88;  // section table: 32-byte entries {kind, owner, element size, pad, offset, count}
  struct Case {
    std::string name, expected;
    std::function<void(Bytes&)> mutate;
  };
  const std::vector<Case> cases = {
      {"section offset past the end", "outside the payload", [&](Bytes& b) { poke<uint64_t>(b, kTable + 16, b.size() * 2); }},
      {"section count past the end", "run past the end", [&](Bytes& b) { poke<uint64_t>(b, kTable + 24, uint64_t{1} << 60); }},
      {"section kind unknown", "unknown kind", [&](Bytes& b) { poke<uint32_t>(b, kTable, 99u); }},
      {"overlapping sections", "overlaps", [&](Bytes& b) { poke<uint64_t>(b, kTable + 32 + 16, peek<uint64_t>(b, kTable + 16)); }},
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
      {"bad list rule", "list rule", [&](Bytes& b) { poke<uint32_t>(b, 84, 7u); }},
      {"wrong version", "format version", [&](Bytes& b) { poke<uint32_t>(b, 8, 99u); }},
  };
  for (const Case& k : cases) {
    SCOPED_TRACE(k.name);
    Bytes hostile = valid;
    k.mutate(hostile);
    sdf::reseal_sdf_cache(hostile);
    expect_refused_everywhere(hostile, k.expected);
  }
}

// sdf-bricks' brick fields ride in the same file: a bit-identical round trip, a cache without
// them (or with other parameters) stale for sdf-bricks but still good for the exact backends,
// and hostile brick sections refused.
TEST_F(SdfCacheTest, BrickFieldsRoundTripAndAreChecked) {
  const sdf::BrickFieldParams bricks{16, 3, sdf::SdfFormat::f16};
  sdf::SceneSdf with = sdf::build_scene_sdf(*scene_, small_grid(), small_hash(), &bricks);
  ASSERT_EQ(with.brick_fields.size(), scene_->meshes.size());
  const fs::path path = dir_.path() / "bricks.sdfcache";
  sdf::write_sdf_cache(path, *scene_, with, small_grid());
  const sdf::SceneSdf loaded = sdf::load_sdf_cache(path, *scene_, small_grid(), small_hash(), &bricks);
  ASSERT_EQ(loaded.brick_fields.size(), 1u);
  const sdf::BrickField &a = with.brick_fields[0], &b = loaded.brick_fields[0];
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
    sdf::load_sdf_cache(path, *scene_, small_grid(), small_hash(), &other);
    ADD_FAILURE() << "a cache with other brick parameters was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--sdf-format f16, requested"), std::string::npos) << e.what();
  }
  try {
    sdf::load_sdf_cache(write_valid(), *scene_, small_grid(), small_hash(), &bricks);
    ADD_FAILURE() << "a cache without brick fields was accepted for sdf-bricks";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("holds no brick fields"), std::string::npos) << e.what();
  }
  // obtain_scene_sdf completes such a cache (exact structures loaded, brick fields added and
  // written back), and refuses one with other brick parameters under the default policy.
  std::ostringstream log;
  const fs::path plain = write_valid();
  const sdf::SceneSdf completed =
      sdf::obtain_scene_sdf(*scene_, small_grid(), small_hash(), {plain.string(), sdf::BadCachePolicy::Refuse}, log, &bricks);
  EXPECT_EQ(completed.brick_fields.size(), 1u);
  EXPECT_NE(log.str().find("added brick fields"), std::string::npos) << log.str();
  EXPECT_NO_THROW(sdf::load_sdf_cache(plain, *scene_, small_grid(), small_hash(), &bricks));
  EXPECT_THROW(
      sdf::obtain_scene_sdf(*scene_, small_grid(), small_hash(), {plain.string(), sdf::BadCachePolicy::Refuse}, log, &other),
      Error);
  const Bytes valid = read_all(path);
  const sdf::SdfCacheContents c = sdf::decode_sdf_cache(valid, "valid");
  auto section = [&](const std::string& name) {
    for (const sdf::SdfCacheSection& s : c.sections)
      if (s.name == name) return s;
    throw std::logic_error("no section " + name);
  };
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
      {"bad brick parameters", "brick field parameters", [&](Bytes& b) { poke<uint32_t>(b, 44, 2u); }},
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
