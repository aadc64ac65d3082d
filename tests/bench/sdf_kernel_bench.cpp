// How close the SDF kernels run to the device's limit (issue 14), two commands:
//   ceiling    point-triangle distances per second of sdf_triangle.glsl's closest_on_triangle at full
//              occupancy: triangles from registers, one coherent fetch, or a divergent gather per lane;
//   breakdown  the real sdf-octree / sdf-hash kernel's frame time per part: each part done twice
//              (SDF_REPEAT_* in sdf_scene_distance.glsl) against the plain kernel, frames alternating,
//              and the SIMD rows' step efficiency (mean over max steps of 8 neighbouring pixels).
// Run by harness/scripts/run_kernel_bench.sh; figures in tests/bench/README.md.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "harness/cli_common.h"
#include "renderers/backend_registry.h"
#include "renderers/renderer.h"
#include "renderers/work_counters.h"
#include "renderers/vulkan/compute_kernel.h"
#include "renderers/vulkan/gpu_buffer.h"
#include "renderers/vulkan/one_time_commands.h"
#include "renderers/vulkan/shader_compiler.h"
#include "scenes/scene_source.h"
#include "util/error.h"

namespace {

using namespace sdfbench;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

struct CeilingOptions {
  std::string device = "lavapipe";
  uint32_t points = 1u << 18;
  uint32_t triangles = 512;
  unsigned repeats = 5;
};

void run_ceiling(const CeilingOptions& o) {
  const Mesh mesh = load_scene("thesis:bunny:1").meshes.at(0);
  const uint32_t table = static_cast<uint32_t>(std::min<size_t>(mesh.triangles.size(), 4096));
  std::vector<glm::vec4> vertices;
  for (uint32_t t = 0; t < table; ++t)
    for (int k = 0; k < 3; ++k) vertices.emplace_back(mesh.positions[mesh.triangles[t][k]], 1.0f);
  VulkanContext context(VulkanContext::Options{o.device, false});
  GpuBuffer vertex_table(context, vertices.size() * sizeof(glm::vec4),
                         VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                         GpuBuffer::Use::Upload, "ceiling triangles");
  vertex_table.write(vertices.data(), vertices.size() * sizeof(glm::vec4));
  vertex_table.texel_view(VK_FORMAT_R32G32B32A32_SFLOAT, sizeof(glm::vec4));
  GpuBuffer result(context, size_t(o.points) * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                   GpuBuffer::Use::Readback, "ceiling result");
  struct Push {
    glm::vec4 box;
    uint32_t triangles, table_size;
  } push{};
  const glm::vec3 extent = mesh.bounds.max - mesh.bounds.min;
  const float edge = 1.2f * std::max({extent.x, extent.y, extent.z});
  push.box = glm::vec4(0.5f * (mesh.bounds.min + mesh.bounds.max) - 0.5f * edge, edge);
  push.triangles = o.triangles;
  push.table_size = table;

  std::printf("device %s; %u points x %u triangles per dispatch (bunny triangles, points in its box), median of %u\n",
              context.info().name.c_str(), o.points, o.triangles, o.repeats);
  std::printf("%-18s %10s %14s\n", "variant", "ms", "M distances/s");
  const std::vector<std::pair<const char*, const char*>> variants = {
      {"registers", "#define REGISTERS\n"},
      {"texel coherent", "#define COHERENT\n"},
      {"texel divergent", ""},
      {"storage coherent", "#define STORAGE\n#define COHERENT\n"},
      {"storage divergent", "#define STORAGE\n"}};
  for (const auto& [variant, defines] : variants) {
    const std::vector<uint32_t> spirv = compile_shader("triangle_distance_ceiling.comp", defines);
    ComputeKernel kernel(context, spirv,
                         {{0, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, &vertex_table},
                          {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &result},
                          {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &vertex_table}},
                         sizeof(Push));
    std::vector<double> ms;
    for (unsigned r = 0; r <= o.repeats; ++r) {  // the first is a warm-up
      const auto start = std::chrono::steady_clock::now();
      run_one_time_commands(context, [&](VkCommandBuffer cmd) {
        kernel.bind(cmd);
        kernel.push(cmd, &push, sizeof(push));
        vkCmdDispatch(cmd, (o.points + 63) / 64, 1, 1);
      });
      const double elapsed = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
      if (r > 0) ms.push_back(elapsed);
    }
    std::vector<float> nearest(o.points);
    result.read(nearest.data(), nearest.size() * sizeof(float));
    if (!std::all_of(nearest.begin(), nearest.end(), [](float d) { return d >= 0.0f && d < 1e30f; }))
      throw Error("ceiling: the kernel returned no distance for some point");
    const double m = median(ms);
    std::printf("%-18s %10.1f %14.1f\n", variant, m, double(o.points) * o.triangles / (m * 1e3));
  }
}

struct BreakdownOptions {
  BackendOptions backend;
  std::string backend_name = "sdf-octree";
  std::string scene = "thesis:bunny:1000";
  std::string size = "640x360";
  std::string mode = "primary";
  unsigned frames = 5;
};

// Mean over max of the per-pixel steps in each SIMD vector (a 4x2 pixel block, render_main.glsl's
// local_pixel): the share of lane-steps doing work.
double step_efficiency(const FrameImages& images) {
  double sum = 0.0, max_sum = 0.0;
  for (uint32_t y0 = 0; y0 < images.height; y0 += 2)
    for (uint32_t x0 = 0; x0 < images.width; x0 += 4) {
      uint32_t block_max = 0, lanes = 0;
      for (uint32_t y = y0; y < std::min(images.height, y0 + 2); ++y)
        for (uint32_t x = x0; x < std::min(images.width, x0 + 4); ++x) {
          const uint32_t s = images.steps[size_t(y) * images.width + x];
          sum += s;
          block_max = std::max(block_max, s);
          ++lanes;
        }
      max_sum += double(block_max) * lanes;
    }
  return max_sum > 0.0 ? sum / max_sum : 1.0;
}

FrameRequest timed_request(const BreakdownOptions& o) {
  const ImageSize size = parse_size(o.size);
  FrameRequest request;
  request.width = size.width;
  request.height = size.height;
  request.mode = parse_mode_option(o.mode);
  request.readback = false;
  return request;
}

// One renderer per kernel variant (#defines), prepared and warmed up; then o.frames rounds of a
// frame from each in turn: the median frame ms of each.
std::vector<double> alternate_variants(const BreakdownOptions& o, const Scene& scene,
                                       const std::vector<std::string>& defines,
                                       std::vector<std::unique_ptr<Renderer>>& renderers) {
  const FrameRequest request = timed_request(o);
  for (const std::string& d : defines) {
    BackendOptions options = o.backend;
    options.kernel_defines = d;
    renderers.push_back(create_renderer(o.backend_name, options));
    renderers.back()->prepare(scene);
    renderers.back()->render(request);  // warm-up: compiles the kernel
  }
  std::vector<std::vector<double>> ms(defines.size());
  for (unsigned f = 0; f < o.frames; ++f)
    for (size_t v = 0; v < defines.size(); ++v) {
      const FrameResult frame = renderers[v]->render(request);
      ms[v].push_back(frame.device_ms >= 0.0 ? frame.device_ms : frame.wall_ms);
    }
  std::vector<double> medians;
  for (const auto& m : ms) medians.push_back(median(m));
  return medians;
}

FrameResult instrumented_frame(const BreakdownOptions& o, Renderer& renderer) {
  FrameRequest counted = timed_request(o);
  counted.counters = true;
  counted.readback = true;
  return renderer.render(counted);
}

// The plain kernel against one with extra #defines (an optimisation being tried): times, and
// whether the steps and the images are the same.
void run_versus(const BreakdownOptions& o, const std::string& defines) {
  const Scene scene = load_scene(o.scene);
  std::vector<std::unique_ptr<Renderer>> renderers;
  const std::vector<double> ms = alternate_variants(o, scene, {"", defines}, renderers);
  const FrameResult a = instrumented_frame(o, *renderers[0]), b = instrumented_frame(o, *renderers[1]);
  size_t steps_differ = 0, colour_differ = 0;
  for (size_t i = 0; i < a.images.steps.size(); ++i) steps_differ += a.images.steps[i] != b.images.steps[i];
  for (size_t i = 0; i < a.images.color.size(); ++i) colour_differ += a.images.color[i] != b.images.color[i];
  std::printf("plain %.1f ms, variant %.1f ms: %.3fx; pixels whose steps differ %zu, colour differs %zu\n", ms[0], ms[1],
              ms[0] / ms[1], steps_differ, colour_differ);
}

void run_breakdown(const BreakdownOptions& o) {
  const Scene scene = load_scene(o.scene);
  const ImageSize size = parse_size(o.size);
  const std::vector<std::pair<std::string, std::string>> variants = {
      {"plain", ""},
      {"locate", "SDF_REPEAT_LOCATE"},
      {"boxes", "SDF_REPEAT_BOXES"},
      {"instance", "SDF_REPEAT_INSTANCE"},
      {"scan", "SDF_REPEAT_SCAN"},
      {"distance", "SDF_REPEAT_DISTANCE"},
      {"exact", "SDF_REPEAT_EXACT"},
  };
  std::vector<std::string> defines;
  for (const auto& [name, define] : variants) defines.push_back(define.empty() ? "" : "#define " + define + " 2\n");
  std::vector<std::unique_ptr<Renderer>> renderers;
  const std::vector<double> ms = alternate_variants(o, scene, defines, renderers);
  const FrameResult instrumented = instrumented_frame(o, *renderers[0]);
  const double plain = ms[0];
  std::printf("%s on %s, %s %ux%u, %s; median of %u frames each, variants alternating\n", o.backend_name.c_str(),
              renderers[0]->device_name().c_str(), o.scene.c_str(), size.width, size.height, o.mode.c_str(), o.frames);
  const WorkCounters& c = instrumented.counters;
  const double rays = double(std::max<uint64_t>(instrumented.rays, 1));
  std::printf("per ray: ");
  for (size_t k = 0; k < c.size(); ++k)
    if (c[k]) std::printf("%s %.2f  ", counter_names()[k], double(*c[k]) / rays);
  std::printf("\nSIMD step efficiency (4x2-pixel vectors): %.1f %%\n", 100.0 * step_efficiency(instrumented.images));
  std::printf("%-10s %10s %12s %8s\n", "part x2", "ms", "part ms", "share");
  std::printf("%-10s %10.1f %12s %8s\n", "plain", plain, "", "");
  double parts = 0.0;
  for (size_t v = 1; v < variants.size(); ++v) {
    const double m = ms[v];
    parts += m - plain;
    std::printf("%-10s %10.1f %12.1f %7.1f%%\n", variants[v].first.c_str(), m, m - plain, 100.0 * (m - plain) / plain);
  }
  std::printf("%-10s %10s %12.1f %7.1f%%  (ray setup, shading, loop control, what no part covers)\n", "rest", "",
              plain - parts, 100.0 * (plain - parts) / plain);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"SDF kernel ceiling and time breakdown (issue 14)"};
  app.require_subcommand(1);
  CeilingOptions ceiling;
  CLI::App* c = app.add_subcommand("ceiling", "point-triangle distances per second at full occupancy");
  c->add_option("--device", ceiling.device, "Vulkan device")->capture_default_str();
  c->add_option("--points", ceiling.points, "invocations (points) per dispatch")->capture_default_str();
  c->add_option("--triangles", ceiling.triangles, "distances per invocation")->capture_default_str();
  c->add_option("--repeats", ceiling.repeats, "timed dispatches per variant")->capture_default_str();
  BreakdownOptions breakdown;
  CLI::App* b = app.add_subcommand("breakdown", "the SDF kernel's time per part");
  b->add_option("--backend", breakdown.backend_name, "sdf-octree | sdf-hash")->capture_default_str();
  b->add_option("--scene", breakdown.scene, "scene")->capture_default_str();
  b->add_option("--size", breakdown.size, "WIDTHxHEIGHT")->capture_default_str();
  b->add_option("--mode", breakdown.mode, "primary | shadow | whitted")->capture_default_str();
  b->add_option("--frames", breakdown.frames, "timed frames per variant")->capture_default_str();
  add_backend_options(*b, breakdown.backend);
  std::string versus;
  b->add_option("--versus", versus, "instead of the breakdown: the plain kernel against one with these #defines "
                                    "(e.g. 'SDF_X=1;SDF_Y=2')");
  try {
    app.parse(argc, argv);
    if (c->parsed()) run_ceiling(ceiling);
    if (b->parsed() && versus.empty()) run_breakdown(breakdown);
    if (b->parsed() && !versus.empty()) {
      std::string defines;
      for (size_t start = 0; start <= versus.size();) {
        const size_t end = std::min(versus.find(';', start), versus.size());
        std::string item = versus.substr(start, end - start);
        if (const size_t eq = item.find('='); eq != std::string::npos) item[eq] = ' ';
        if (!item.empty()) defines += "#define " + item + "\n";
        start = end + 1;
      }
      run_versus(breakdown, defines);
    }
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::cerr << "sdfbench_kernel_bench: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
