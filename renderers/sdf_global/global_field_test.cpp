// sdf-global (issue 29): the scene-wide field's samples and bound against brute-force distances
// over all triangles of all instances, through the kernel's own sampling code (brick_sample.glsl
// compiled as C++); its brick lists against the instances' surfaces; the backend's images against
// Embree; its field hits' accuracy; its errors.
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <set>

#include <gtest/gtest.h>

#include "harness/cli_common.h"
#include "harness/csv.h"
#include "harness/image_agreement.h"
#include "renderers/backend_registry.h"
#include "renderers/renderer.h"
#include "renderers/sdf_global/cell_triangle_refs.h"
#include "renderers/sdf_global/global_field.h"
#include "renderers/sdf/scene_hash.h"
#include "renderers/sdf_bricks/brick_gpu_arrays.h"
#include "renderers/work_counters.h"
#include "scenes/thesis_layout.h"
#include "tests/test_support.h"
#include "util/error.h"

namespace sdfbench {
namespace {

// Brute force over every triangle of every instance: the distance to the union of the surfaces.
float brute_force_scene(const Scene& scene, const glm::vec3& p) {
  float best = std::numeric_limits<float>::max();
  for (const Instance& instance : scene.instances) {
    const glm::vec3 local(instance.transform.world_to_object() * glm::vec4(p, 1.0f));
    best = std::min(best, sdf::brute_force_distance(scene.meshes[instance.mesh], local) * instance.transform.scale);
  }
  return best;
}

struct GlobalCase {
  const char* mesh;
  uint32_t objects;
  float voxel;  // 0: auto
  sdf::SdfFormat format;
};

std::string case_name(const testing::TestParamInfo<GlobalCase>& info) {
  return std::string(info.param.mesh) + "_" + std::to_string(info.param.objects) + "_" +
         (info.param.voxel > 0 ? std::to_string(int(info.param.voxel * 100)) : std::string("auto")) + "_" +
         sdf::to_string(info.param.format);
}

class GlobalFieldVsBruteForce : public testing::TestWithParam<GlobalCase> {
 protected:
  void SetUp() override {
    const GlobalCase c = GetParam();
    scene_ = make_thesis_scene({c.mesh, c.objects, 1});
    sdf::SceneHashParams hash;
    hash.octree_depth = 0;
    sdf::GlobalFieldParams params;
    params.voxel = c.voxel;
    params.format = c.format;
    sdf_ = sdf::build_scene_sdf(scene_, sdf::MeshGridParams{}, hash, {sdf::structure_request(params)});
  }
  Scene scene_;
  sdf::SceneSdf sdf_;
};

// The bound the tracer steps by never exceeds the distance to the nearest surface (in stored
// bricks, empty bricks, outside the lattice), and near surfaces it is within about a voxel of it.
TEST_P(GlobalFieldVsBruteForce, BoundNeverExceedsTheDistance) {
  const sdf::BrickField& field = sdf_.get<sdf::GlobalFieldStructure>().field.field;
  const BrickGpuArrays arrays = flatten_brick_fields({field});
  shading::BrickCpuSampler sampler(arrays);
  const auto info = sampler.brick_field_info(0);
  EXPECT_GT(field.stored_bricks(), 0u);
  EXPECT_LT(field.stored_bricks(), field.brick_count() / 2);  // sparse
  std::mt19937 rng(29);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  const glm::vec3 lo = field.origin - 0.1f * (field.box_max() - field.origin);
  const glm::vec3 hi = field.box_max() + 0.1f * (field.box_max() - field.origin);
  size_t stored = 0, near = 0, empty = 0;
  double slack_sum = 0;
  for (int i = 0; i < 1200; ++i) {
    glm::vec3 p = lo + (hi - lo) * glm::vec3(u01(rng), u01(rng), u01(rng));
    if (i % 2 == 0) {  // half near a surface: a random instance's vertex, jittered by up to two voxels
      const Instance& instance = scene_.instances[rng() % scene_.instances.size()];
      const Mesh& mesh = scene_.meshes[instance.mesh];
      p = glm::vec3(instance.transform.object_to_world() * glm::vec4(mesh.positions[rng() % mesh.positions.size()], 1.0f)) +
          2.0f * field.voxel * (glm::vec3(u01(rng), u01(rng), u01(rng)) * 2.0f - 1.0f);
    }
    const float exact = brute_force_scene(scene_, p);
    const auto s = sampler.sample_field(info, p);
    ASSERT_LE(s.bound, exact * (1.0f + 1e-5f) + 1e-5f * field.voxel) << "at (" << p.x << ", " << p.y << ", " << p.z << ")";
    if (s.stored) {
      ++stored;
      if (exact < 0.5f * field.band) ++near, slack_sum += exact - s.bound;
    } else if (glm::all(glm::greaterThanEqual(p, field.origin)) && glm::all(glm::lessThanEqual(p, field.box_max()))) {
      ++empty;
      EXPECT_GE(exact, field.band * (1.0f - 1e-5f));  // no point of an empty brick lies within the band
    }
  }
  EXPECT_GT(stored, 300u);
  EXPECT_GT(empty, 50u);
  ASSERT_GT(near, 200u);
  EXPECT_LT(slack_sum / double(near), field.voxel) << "mean slack in voxels " << slack_sum / double(near) / field.voxel;
}

// A stored sample is the composite's exact magnitude at its lattice point (clamped to the band),
// to within the format's quantization.
TEST_P(GlobalFieldVsBruteForce, LatticeSamplesAreTheClampedSceneDistance) {
  const sdf::BrickField& field = sdf_.get<sdf::GlobalFieldStructure>().field.field;
  size_t checked = 0;
  for (size_t b = 0; b < field.brick_count() && checked < 240; b += 7) {
    if (field.indirection[b] == sdf::kEmptyBrick) continue;
    const glm::uvec3 brick(b % field.bricks.x, (b / field.bricks.x) % field.bricks.y, b / (size_t(field.bricks.x) * field.bricks.y));
    for (uint32_t k : {0u, 146u, 511u}) {
      const glm::uvec3 local(k % 8, (k / 8) % 8, k / 64);
      const glm::vec3 p = field.origin + field.voxel * glm::vec3(brick * sdf::kBrickCells + local);
      const float stored = sdf::atlas_value(field, size_t(field.indirection[b]) * sdf::kBrickSamples + k);
      const float exact = brute_force_scene(scene_, p);
      EXPECT_NEAR(std::abs(stored), std::min(exact, field.band), field.quantization + 1e-5f * field.band)
          << "brick " << b << " sample " << k;
      ++checked;
    }
  }
  EXPECT_GT(checked, 60u);
}

// Every surface point lies in a stored brick that lists its instance (what the exact hits rely on).
TEST_P(GlobalFieldVsBruteForce, BricksListEveryInstanceWhoseSurfaceTheyHold) {
  const sdf::GlobalField& global = sdf_.get<sdf::GlobalFieldStructure>().field;
  const sdf::BrickField& field = global.field;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  for (int n = 0; n < 3000; ++n) {
    const uint32_t i = rng() % scene_.instances.size();
    const Instance& instance = scene_.instances[i];
    const Mesh& mesh = scene_.meshes[instance.mesh];
    const glm::uvec3 tri = mesh.triangles[rng() % mesh.triangles.size()];
    float a = u01(rng), b = u01(rng);
    if (a + b > 1.0f) a = 1.0f - a, b = 1.0f - b;
    const glm::vec3 local = mesh.positions[tri.x] + a * (mesh.positions[tri.y] - mesh.positions[tri.x]) +
                            b * (mesh.positions[tri.z] - mesh.positions[tri.x]);
    const glm::vec3 p(instance.transform.object_to_world() * glm::vec4(local, 1.0f));
    const glm::uvec3 c = glm::min(glm::uvec3(glm::max((p - field.origin) / field.voxel, glm::vec3(0.0f))),
                                  field.bricks * sdf::kBrickCells - 1u);
    const glm::uvec3 brick = c / sdf::kBrickCells;
    const uint32_t slot = field.indirection[brick.x + size_t(field.bricks.x) * (brick.y + size_t(field.bricks.y) * brick.z)];
    ASSERT_NE(slot, sdf::kEmptyBrick) << "instance " << i << " surface point in an empty brick";
    const auto begin = global.list_instances.begin() + global.list_begin[slot];
    const auto end = global.list_instances.begin() + global.list_begin[slot + 1];
    ASSERT_NE(std::find(begin, end, i), end) << "instance " << i << " not listed by the brick holding its surface";
  }
}

// --exact-lists triangles: every triangle is in the set of each reference cell that a point of it
// lies in (points drawn on random triangles of random instances), at two cell sizes; the bricks
// no triangle crosses have no table.
TEST_P(GlobalFieldVsBruteForce, ReferenceCellsListEveryTriangleCrossingThem) {
  const sdf::BrickField& field = sdf_.get<sdf::GlobalFieldStructure>().field.field;
  std::vector<uint32_t> mesh_first(1, 0);
  for (const Mesh& mesh : scene_.meshes) mesh_first.push_back(mesh_first.back() + uint32_t(mesh.triangles.size()));
  for (uint32_t split : {1u, 3u}) {
    const sdf::CellTriangleRefs refs = sdf::build_cell_triangle_refs(scene_, field, split, uint64_t(1) << 31);
    const float cell = field.voxel / float(split);
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u01(0.0f, 1.0f);
    std::set<uint32_t> crossed_bricks;
    for (int n = 0; n < 3000; ++n) {
      const uint32_t i = rng() % scene_.instances.size();
      const Instance& instance = scene_.instances[i];
      const Mesh& mesh = scene_.meshes[instance.mesh];
      const uint32_t t = rng() % mesh.triangles.size();
      const glm::uvec3 tri = mesh.triangles[t];
      float a = u01(rng), b = u01(rng);
      if (a + b > 1.0f) a = 1.0f - a, b = 1.0f - b;
      const glm::vec3 local = mesh.positions[tri.x] + a * (mesh.positions[tri.y] - mesh.positions[tri.x]) +
                              b * (mesh.positions[tri.z] - mesh.positions[tri.x]);
      const glm::vec3 p(instance.transform.object_to_world() * glm::vec4(local, 1.0f));
      const glm::uvec3 g = glm::min(glm::uvec3(glm::max((p - field.origin) / cell, glm::vec3(0.0f))),
                                    field.bricks * refs.cells_per_side - 1u);
      const glm::uvec3 brick = g / refs.cells_per_side, l = g - brick * refs.cells_per_side;
      const uint32_t slot = field.indirection[brick.x + size_t(field.bricks.x) * (brick.y + size_t(field.bricks.y) * brick.z)];
      ASSERT_NE(slot, sdf::kEmptyBrick);
      crossed_bricks.insert(slot);
      ASSERT_NE(refs.brick_tables[slot], sdf::kNoCellTable) << "a brick holding a surface point has no cell table";
      const uint32_t set = refs.cells[refs.brick_tables[slot] + l.x + refs.cells_per_side * (l.y + refs.cells_per_side * l.z)];
      bool listed = false;
      uint32_t listed_instance = sdf::kNoCellTable;
      for (uint32_t k = set + 1; k <= set + refs.sets[set]; ++k) {
        const uint32_t w = refs.sets[k];
        if (w & sdf::kInstanceWord) listed_instance = w & ~sdf::kInstanceWord;
        else listed = listed || (listed_instance == i && w == mesh_first[instance.mesh] + t);
      }
      ASSERT_TRUE(listed) << "split " << split << ": instance " << i << " triangle " << t << " not in the set of a cell it crosses";
    }
    size_t tables = 0;
    for (uint32_t table : refs.brick_tables) tables += table != sdf::kNoCellTable;
    EXPECT_LT(tables, refs.brick_tables.size()) << "every stored brick has a table: the band's bricks are not told apart";
    EXPECT_GE(tables, crossed_bricks.size());
    EXPECT_GT(refs.references, 0u);
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, GlobalFieldVsBruteForce,
                         testing::Values(GlobalCase{"teapot", 12, 0.0f, sdf::SdfFormat::f32},
                                         GlobalCase{"bunny", 8, 0.5f, sdf::SdfFormat::u8},
                                         GlobalCase{"monkey", 8, 0.35f, sdf::SdfFormat::f16}),
                         case_name);

TEST(GlobalField, ParametersAndLimitsAreErrorsNamingTheFlag) {
  const ParamSpec voxel = catalogue_spec("global_voxel");  // a copy: GCC 14 takes the reference for a dangling one
  EXPECT_THROW(parse_param_value(voxel, "0"), Error);
  EXPECT_THROW(parse_param_value(voxel, "-1"), Error);
  EXPECT_THROW(parse_param_value(voxel, "0.5x"), Error);
  EXPECT_THROW(parse_param_value(voxel, "nan"), Error);
  EXPECT_THROW(parse_param_value(voxel, "1e-50"), Error);  // below the range: never measured as another value
  EXPECT_EQ(parse_param_value(voxel, "0.50"), "0.5");  // one spelling: one configuration key
  EXPECT_EQ(parse_param_value(voxel, "auto"), "auto");

  const Scene scene = make_thesis_scene({"sphere", 4, 1});
  sdf::SceneHashParams hash;
  hash.octree_depth = 0;
  sdf::SceneSdf sdf = sdf::build_scene_sdf(scene, sdf::MeshGridParams{}, hash);
  sdf::GlobalFieldParams tiny;
  tiny.voxel = 1e-4f;
  try {
    sdf::build_global_field(scene, sdf, sdf::MeshGridParams{}, tiny);
    ADD_FAILURE() << "a field of billions of bricks was built";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--global-voxel"), std::string::npos) << e.what();
  }
  sdf::GlobalFieldParams capped;
  capped.voxel = 0.1f;
  capped.max_bytes = 1 << 16;
  try {
    sdf::build_global_field(scene, sdf, sdf::MeshGridParams{}, capped);
    ADD_FAILURE() << "the structure memory cap was not respected";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--max-structure-mb"), std::string::npos) << e.what();
  }
}

// Every format and both fetch paths draw what Embree draws (exact hits), in primary and shadow,
// clean under the validation layer; a step is one field sample and no point-triangle distance.
TEST(SdfGlobal, FormatsAndFetchPathsAgreeWithEmbreeUnderValidation) {
  const Scene scene = make_thesis_scene({"teapot", 30, 1});
  const FrameImages expected[] = {test::render_frame("embree", scene, RenderMode::Primary, 96, 54),
                                  test::render_frame("embree", scene, RenderMode::Shadow, 96, 54)};
  for (const auto& [format, fetch] : std::vector<std::pair<const char*, const char*>>{
           {"f32", "texel"}, {"f16", "sampler"}, {"u8", "texel"}, {"u8", "sampler"}}) {
    BackendOptions options;
    options.validation = true;
    options.params.set("sdf_format", format);
    options.params.set("brick_fetch", fetch);
    auto renderer = create_renderer("sdf-global", options);
    renderer->prepare(scene);
    EXPECT_EQ(renderer->structure_stats()->resolved.rfind(std::string("brick_fetch=") + fetch + " voxel=", 0), 0u)
        << renderer->structure_stats()->resolved;
    for (RenderMode mode : {RenderMode::Primary, RenderMode::Shadow}) {
      const FrameResult frame = renderer->render(FrameRequest{96, 54, mode, true, {}, true});
      const Agreement g = compare_frames(frame.images, expected[mode == RenderMode::Shadow ? 1 : 0]);
      EXPECT_EQ(check_thresholds(g, AgreementThresholds{}), "") << format << " " << fetch << " " << to_string(mode);
      EXPECT_EQ(frame.counters[COUNTER_FIELD_SAMPLES].value_or(0), frame.counters[COUNTER_STEPS].value_or(1)) << format;
      EXPECT_FALSE(frame.counters[COUNTER_TRIANGLE_EVALS].has_value());
      EXPECT_GT(frame.counters[COUNTER_TRIANGLE_TESTS].value_or(0), 0u);
    }
    EXPECT_EQ(renderer->validation_messages(), 0u) << format << " " << fetch;
  }
}

// --hit field: the field's own crossing, its depth error reported in voxels (under a couple),
// far from the exact hits' rounding error; the gate stays the usual one.
TEST(SdfGlobal, FieldHitsReportTheirAccuracyInVoxels) {
  const Scene scene = make_thesis_scene({"bunny", 10, 1});
  const FrameImages expected = test::render_frame("embree", scene, RenderMode::Primary, 160, 90);
  BackendOptions field_options, exact_options;
  field_options.params.set("hit", "field");
  auto field = create_renderer("sdf-global", field_options);
  auto exact = create_renderer("sdf-global", exact_options);
  field->prepare(scene);
  exact->prepare(scene);
  const FrameRequest request{160, 90, RenderMode::Primary, true};
  const Agreement f = compare_frames(field->render(request).images, expected, field->structure_stats()->instance_voxels);
  const Agreement e = compare_frames(exact->render(request).images, expected, exact->structure_stats()->instance_voxels);
  ASSERT_TRUE(f.depth_p99_voxels && e.depth_p99_voxels);
  EXPECT_LT(*f.depth_p99_voxels, 2.0);
  EXPECT_GT(*f.depth_p99_voxels, 10.0 * *e.depth_p99_voxels);
  EXPECT_LT(*e.depth_p99_voxels, 0.01);
  EXPECT_GE(f.hit_percent, 99.0);
  EXPECT_EQ(check_thresholds(e, AgreementThresholds{}), "");
}

TEST(SdfGlobal, OptionsOfOtherBackendsAreUserErrors) {
  const std::string small = " --scene thesis:sphere:3 --size 32x18 --frames 1 --warmup 0";
  for (const auto& [args, words] : std::vector<std::pair<std::string, std::string>>{
           {"render --backend sdf-bricks --global-voxel 0.5" + small, "--global-voxel is a parameter of sdf-global"},
           {"render --backend sdf-global --voxels 32" + small, "--voxels is a parameter of sdf-bricks"},
           {"render --backend sdf-global --global-voxel 0" + small, "--global-voxel"},
           {"render --backend sdf-global --global-voxel 0.00001" + small, "--global-voxel"},
           // 2^26 bricks: refused before their bookkeeping (2.7 GB) is allocated (issue 39).
           {"render --backend sdf-global --global-voxel 0.045 --scene thesis:sphere:1000 --size 16x16 --frames 1 --warmup 0",
            "of bookkeeping to build them, more than --max-structure-mb allows (2048)"},
           {"render --backend sdf-global --hit thesis" + small, "--hit thesis"},
           {"render --backend sdf-global --cell-bound" + small, "--cell-bound"}}) {
    const test::CommandResult r = test::run_sdfbench(args);
    EXPECT_EQ(r.exit_code, 1) << args << "\n" << r.output;
    EXPECT_NE(r.output.find("sdfbench: error:"), std::string::npos) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(words), std::string::npos) << args << "\n" << r.output;
  }
}

// The sweep varies the global voxel (a CSV column), every row agreeing and reporting its bytes.
TEST(SdfGlobal, SweepVariesTheGlobalVoxel) {
  test::TempDir dir;
  const auto csv = dir.path() / "sweep.csv";
  const test::CommandResult r = test::run_sdfbench(
      "sweep --scene thesis:bunny:6 --backend sdf-global --global-voxel 0.5,1 --sdf-format f16 "
      "--size 48x27 --check-size 48x27 --frames 1 --warmup 0 --csv " + csv.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const CsvTable table = read_csv(csv);
  ASSERT_EQ(table.rows.size(), 2u);
  std::set<std::string> seen;
  for (const auto& row : table.rows) {
    seen.insert(row[table.column("global_voxel")]);
    EXPECT_EQ(row[table.column("agreement")], "ok");
    EXPECT_FALSE(row[table.column("structure_bytes")].empty());
  }
  EXPECT_EQ(seen, (std::set<std::string>{"0.5", "1"}));
  const auto bytes = [&](size_t r) { return std::stod(table.rows[r][table.column("structure_bytes")]); };
  EXPECT_GT(bytes(0), bytes(1));  // a finer field needs more bytes
}

}  // namespace
}  // namespace sdfbench
