// --brick-fetch sampler against brute force (issue 39): the sampled fields' sampling code run on
// the Vulkan device through the hardware filter (renderers/sdf_bricks/brick_field_probe.comp), at
// points near and far from the surface. The bound it returns must never exceed the exact distance
// over all triangles, and its filtered value must lie within the slack the kernels allow the filter
// (brick_filter_slack) of the exact trilinear that the texel path computes (BrickCpuSampler).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>

#include "renderers/sdf_bricks/brick_field.h"
#include "renderers/sdf/mesh_distance_grid.h"
#include "renderers/sdf_bricks/brick_field_tables.h"
#include "renderers/sdf_bricks/brick_gpu_arrays.h"
#include "renderers/vulkan/compute_kernel.h"
#include "renderers/vulkan/gpu_buffer.h"
#include "renderers/vulkan/one_time_commands.h"
#include "renderers/vulkan/shader_compiler.h"
#include "renderers/vulkan/vulkan_context.h"
#include "scenes/mesh.h"
#include "tests/brick_field_cases.h"

namespace sdfbench {
namespace {

using test::FieldCase;

struct DeviceSample {
  float bound, value, stored, unused;
};

// sample_field() at each point on the device, through the sampler (with the kernels' defines).
std::vector<DeviceSample> sample_on_device(const VulkanContext& context, const BrickGpuArrays& arrays,
                                           const std::vector<glm::vec4>& points, shading::SdfParams& params) {
  const BrickFieldTables tables(context, arrays, true, params, "");
  GpuBuffer params_buffer(context, sizeof(params), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, GpuBuffer::Use::Upload,
                          "probe parameters");
  params_buffer.write(&params, sizeof(params));
  GpuBuffer point_buffer(context, points.size() * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                         GpuBuffer::Use::Upload, "probe points");
  point_buffer.write(points.data(), points.size() * sizeof(glm::vec4));
  GpuBuffer samples(context, points.size() * sizeof(DeviceSample), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                    GpuBuffer::Use::Readback, "probe samples");
  std::vector<KernelBinding> bindings = {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &point_buffer},
                                         {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &samples},
                                         {8, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, &params_buffer}};
  tables.add_bindings(bindings);
  std::string defines = "#define BRICK_SAMPLER 1\n";
  if (arrays.format == sdf::SdfFormat::u8) defines += "#define BRICK_U8 1\n";
  struct Push {
    uint32_t points, mesh;
  } push{uint32_t(points.size()), 0u};
  ComputeKernel kernel(context, compile_shader("brick_field_probe.comp", defines), bindings, sizeof(Push));
  run_one_time_commands(context, [&](VkCommandBuffer cmd) {
    kernel.bind(cmd);
    kernel.push(cmd, &push, sizeof(push));
    vkCmdDispatch(cmd, (push.points + 63) / 64, 1, 1);
  });
  std::vector<DeviceSample> result(points.size());
  samples.read(result.data(), result.size() * sizeof(DeviceSample));
  return result;
}

class SamplerFetchVsBruteForce : public testing::TestWithParam<FieldCase> {};

TEST_P(SamplerFetchVsBruteForce, BoundNeverExceedsTheDistanceAndTheFilterStaysInItsSlack) {
  const FieldCase c = GetParam();
  const Mesh mesh = load_obj(builtin_mesh_path(c.mesh), c.mesh);
  const sdf::MeshDistanceGrid grid = sdf::build_mesh_distance_grid(mesh, sdf::MeshGridParams{});
  const std::vector<sdf::BrickField> fields = {
      sdf::build_brick_field(mesh, grid, {c.voxels, 4, c.format})};
  const sdf::BrickField& field = fields[0];
  const BrickGpuArrays arrays = flatten_brick_fields(fields);

  // Half the points within two voxels of a vertex (in stored bricks, where the filter is used),
  // half anywhere in the lattice's box and a margin around it.
  std::mt19937 rng(39);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  const glm::vec3 lo = field.origin - 0.2f * (field.box_max() - field.origin);
  const glm::vec3 hi = field.box_max() + 0.2f * (field.box_max() - field.origin);
  std::vector<glm::vec4> points;
  for (int i = 0; i < 4000; ++i) {
    glm::vec3 p = lo + (hi - lo) * glm::vec3(u01(rng), u01(rng), u01(rng));
    if (i % 2 == 0)
      p = mesh.positions[rng() % mesh.positions.size()] +
          2.0f * field.voxel * (glm::vec3(u01(rng), u01(rng), u01(rng)) * 2.0f - 1.0f);
    points.emplace_back(p, 1.0f);
  }

  VulkanContext context(VulkanContext::Options{"lavapipe", true});
  shading::SdfParams params{};
  const std::vector<DeviceSample> device = sample_on_device(context, arrays, points, params);
  EXPECT_EQ(context.validation_messages(), 0u);
  ASSERT_GT(params.options.z, 0.0f) << "the tables set no filter slack";
  const float filter_slack = params.options.z * field.voxel + params.options.w * field.band;  // brick_filter_slack

  shading::BrickCpuSampler texel_path(arrays);
  const auto info = texel_path.brick_field_info(0);
  size_t stored = 0;
  double largest_filter_error = 0.0;
  for (size_t i = 0; i < points.size(); ++i) {
    const glm::vec3 p(points[i]);
    const float exact = sdf::brute_force_distance(mesh, p);
    ASSERT_LE(device[i].bound, exact * (1.0f + 1e-5f) + 1e-6f)
        << "the sampler's bound passes the distance at (" << p.x << ", " << p.y << ", " << p.z << ")";
    const auto t = texel_path.sample_field(info, p);
    ASSERT_EQ(device[i].stored != 0.0f, t.stored) << "point " << i;
    if (!t.stored) continue;
    ++stored;
    const double filter_error = std::abs(double(device[i].value) - double(t.value));
    largest_filter_error = std::max(largest_filter_error, filter_error);
    ASSERT_LE(filter_error, filter_slack) << "the filtered value leaves the filter's slack at (" << p.x << ", " << p.y
                                          << ", " << p.z << "): device " << device[i].value << ", exact trilinear "
                                          << t.value;
  }
  EXPECT_GT(stored, 1500u);
  // The filter does differ from the exact trilinear (else this test would not see the hardware).
  EXPECT_GT(largest_filter_error, 0.0) << "the device's filter equals the exact trilinear everywhere";
  std::printf("%s: %zu stored-brick points, largest filter error %.3g of a slack %.3g (mesh units)\n",
              test::field_case_name({c, 0}).c_str(), stored, largest_filter_error, double(filter_slack));
}

INSTANTIATE_TEST_SUITE_P(Meshes, SamplerFetchVsBruteForce,
                         testing::Values(FieldCase{"bunny", 32, sdf::SdfFormat::f32},
                                         FieldCase{"teapot", 48, sdf::SdfFormat::u8},
                                         FieldCase{"monkey", 40, sdf::SdfFormat::f16}),
                         test::field_case_name);

}  // namespace
}  // namespace sdfbench
