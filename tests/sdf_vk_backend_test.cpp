// The Vulkan SDF backends (sdf-hash, sdf-octree, sdf-bricks, sdf-global): they draw what Embree draws, run clean under
// the validation layer, and trace exactly what the CPU reference sphere tracer (sdf-cpu) traces.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "harness/image_agreement.h"
#include "renderers/backend_registry.h"
#include "renderers/renderer.h"
#include "renderers/work_counters.h"
#include "renderers/shading/gpu_types.h"
#include "scenes/thesis_layout.h"
#include "util/error.h"

namespace sdfbench {
namespace {

constexpr RenderMode kModes[] = {RenderMode::Primary, RenderMode::Shadow};

class SdfVkVsEmbree : public testing::TestWithParam<std::string> {};

TEST_P(SdfVkVsEmbree, ImagesAgreeUnderValidation) {
  const Scene scene = make_thesis_scene({"bunny", 300, 1});
  auto reference = create_renderer("embree", BackendOptions{});
  reference->prepare(scene);
  BackendOptions options;
  options.validation = true;
  auto renderer = create_renderer(GetParam(), options);
  renderer->prepare(scene);
  for (RenderMode mode : kModes) {
    SCOPED_TRACE(to_string(mode));
    const FrameImages expected = reference->render(FrameRequest{96, 54, mode, true}).images;
    const FrameResult result = renderer->render(FrameRequest{96, 54, mode, true});
    size_t instance_pixels = 0;
    for (uint32_t id : result.images.instance_id) instance_pixels += id < shading::FLOOR_INSTANCE_VALUE;
    EXPECT_GT(instance_pixels, 400u);  // enough instance pixels for a meaningful id %
    const Agreement g = compare_frames(result.images, expected);
    EXPECT_GE(g.hit_percent, 99.5);
    EXPECT_GE(g.id_percent, 99.0);
    EXPECT_LE(g.depth_p99, 1e-3);
    EXPECT_GE(g.psnr, 30.0);
  }
  EXPECT_EQ(renderer->validation_messages(), 0u);
}

// Every SDF backend on the Vulkan device, as the registry lists them.
std::vector<std::string> vulkan_sdf_backends() {
  std::vector<std::string> names;
  for (const BackendInfo& b : backends())
    if (b.vulkan && is_sdf(b.kind)) names.push_back(b.name);
  return names;
}

INSTANTIATE_TEST_SUITE_P(Backends, SdfVkVsEmbree, testing::ValuesIn(vulkan_sdf_backends()), [](const auto& info) {
  std::string name = info.param;
  name.erase(name.find('-'), 1);
  return name;
});

// Same algorithm as the CPU sphere tracer: the same hits (ids and triangles) wherever it hits.
// The exact lists make the distance field independent of hash cell and octree, so even
// sdf-hash (cell 1, no octree) must match sdf-cpu (cell 10, depth 4).
TEST(SdfVkVsCpu, SameHitsAsTheCpuSphereTracer) {
  const Scene scene = make_thesis_scene({"teapot", 20, 3});
  auto cpu = create_renderer("sdf-cpu", BackendOptions{});
  cpu->prepare(scene);
  for (const char* backend : {"sdf-hash", "sdf-octree"}) {
    auto gpu = create_renderer(backend, BackendOptions{});
    gpu->prepare(scene);
    for (RenderMode mode : kModes) {
      const FrameImages expected = cpu->render(FrameRequest{64, 36, mode, true}).images;
      const FrameImages images = gpu->render(FrameRequest{64, 36, mode, true}).images;
      size_t same_id = 0, same_prim = 0;
      for (size_t i = 0; i < images.instance_id.size(); ++i) {
        same_id += images.instance_id[i] == expected.instance_id[i];
        same_prim += images.primitive_id[i] == expected.primitive_id[i];
      }
      // Float contraction may differ between glslang/LLVM and the C++ compiler: a pixel or two.
      const size_t pixels = images.instance_id.size();
      EXPECT_GE(same_id, pixels - 2) << backend << " " << to_string(mode);
      EXPECT_GE(same_prim, pixels - 2) << backend << " " << to_string(mode);
      EXPECT_GE(compare_frames(images, expected).psnr, 40.0) << backend << " " << to_string(mode);
    }
  }
}

// The method at its best (issue 14), options off by default: over-relaxed sphere tracing and the
// per-leaf bound change the path, not what is drawn; over-relaxation is the same on the CPU.
TEST(SdfOptions, OverRelaxationDrawsTheSameAndTracesAsTheCpu) {
  const Scene scene = make_thesis_scene({"bunny", 100, 1});
  BackendOptions plain_options, relaxed;
  relaxed.params.set("over_relax", "1.6");
  relaxed.validation = true;
  auto plain = create_renderer("sdf-octree", plain_options);
  auto gpu = create_renderer("sdf-octree", relaxed);
  auto cpu = create_renderer("sdf-cpu", relaxed);
  for (Renderer* r : {plain.get(), gpu.get(), cpu.get()}) r->prepare(scene);
  {  // shadow mode: primary and shadow rays, one kernel to compile
    const FrameRequest request{96, 54, RenderMode::Shadow, true, std::nullopt, true};
    const FrameResult a = plain->render(request), b = gpu->render(request), c = cpu->render(request);
    const Agreement g = compare_frames(b.images, a.images);
    EXPECT_GE(g.hit_percent, 99.9);
    EXPECT_GE(g.id_percent, 99.9);
    EXPECT_GE(g.psnr, 40.0);
    EXPECT_NE(b.counters[COUNTER_STEPS], a.counters[COUNTER_STEPS]) << "the option changes the march";
    // The CPU tracer takes the same steps, a float contraction apart.
    const double gpu_steps = double(*b.counters[COUNTER_STEPS]), cpu_steps = double(*c.counters[COUNTER_STEPS]);
    EXPECT_NEAR(gpu_steps / cpu_steps, 1.0, 1e-3);
  }
  EXPECT_EQ(gpu->validation_messages(), 0u);
}

TEST(SdfOptions, CellBoundSkipsInstancesAndDrawsTheSame) {
  const Scene scene = make_thesis_scene({"teapot", 50, 2});
  for (const char* backend : {"sdf-octree", "sdf-hash"}) {
    SCOPED_TRACE(backend);
    BackendOptions plain_options, bounded, both;
    bounded.params.set("cell_bound", "1");
    bounded.validation = true;
    both = bounded;  // a relaxed step into a skipped leaf is checked too
    both.params.set("over_relax", "1.8");
    auto plain = create_renderer(backend, plain_options);
    auto gpu = create_renderer(backend, bounded);
    auto relaxed = create_renderer(backend, both);
    for (Renderer* r : {plain.get(), gpu.get(), relaxed.get()}) r->prepare(scene);
    {  // shadow mode: primary and shadow rays, one kernel to compile
      const FrameRequest request{96, 54, RenderMode::Shadow, true, std::nullopt, true};
      const FrameResult a = plain->render(request);
      for (Renderer* r : {gpu.get(), relaxed.get()}) {
        const FrameResult b = r->render(request);
        const Agreement g = compare_frames(b.images, a.images);
        EXPECT_GE(g.hit_percent, 99.9);
        EXPECT_GE(g.id_percent, 99.9);
        EXPECT_GE(g.psnr, 40.0);
        EXPECT_LT(*b.counters[COUNTER_INSTANCE_EVALS], *a.counters[COUNTER_INSTANCE_EVALS]);
      }
    }
    EXPECT_EQ(gpu->validation_messages() + relaxed->validation_messages(), 0u);
  }
  BackendOptions bounded;
  bounded.params.set("cell_bound", "1");
  try {
    check_params_taken(bounded.params, {"sdf-cpu"});
    ADD_FAILURE() << "sdf-cpu accepted --cell-bound";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--cell-bound is a parameter of sdf-hash, sdf-octree"), std::string::npos) << e.what();
  }
}

// --storage-tables reads the same bytes through another descriptor type: the same image, ids,
// depths and work counters, bit for bit, under the validation layer; whitted covers the hit
// shading's fetches (normals, records) and the secondary rays.
TEST(SdfOptions, StorageTablesDrawExactlyTheSame) {
  const Scene scene = make_thesis_scene({"teapot", 30, 4});
  {  // sdf-hash runs the same kernel on other data (SweepCommand.StorageTablesAreAnAxis covers it)
    const char* backend = "sdf-octree";
    BackendOptions storage_options;
    storage_options.params.set("storage_tables", "1");
    storage_options.validation = true;
    auto texel = create_renderer(backend, BackendOptions{});
    auto storage = create_renderer(backend, storage_options);
    texel->prepare(scene);
    storage->prepare(scene);
    // Primary rays reach every table read: shadow rays (any_hit) trace with the same function as
    // closest_hit, and whitted only adds call sites (a storage-buffer whitted kernel takes lavapipe
    // ~13 s to compile, 5x a texel one).
    const FrameRequest request{64, 36, RenderMode::Primary, true, std::nullopt, true};
    const FrameResult a = texel->render(request), b = storage->render(request);
    EXPECT_EQ(a.images.color, b.images.color);
    EXPECT_EQ(a.images.instance_id, b.images.instance_id);
    EXPECT_EQ(a.images.primitive_id, b.images.primitive_id);
    EXPECT_EQ(a.images.depth, b.images.depth);
    for (size_t c = 0; c < a.counters.size(); ++c) EXPECT_EQ(a.counters[c], b.counters[c]) << "counter " << c;
    EXPECT_EQ(storage->validation_messages(), 0u);
  }
  BackendOptions storage;
  storage.params.set("storage_tables", "1");
  try {
    check_params_taken(storage.params, {"sdf-cpu"});
    ADD_FAILURE() << "sdf-cpu accepted --storage-tables";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--storage-tables is a parameter of"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sdfbench
