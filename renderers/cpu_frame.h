#pragma once
// The frame loop of every CPU backend: TBB over 16x16 tiles in an arena of `threads`, each
// pixel shaded by the shared program (cpu_shading.h) over the backend's tracer (or, for a backend
// that traces a tile's rays together, by its own tile shader). counter_kinds: the work counters
// the tracer counts (bit k for COUNTER kind k).
#include <algorithm>
#include <chrono>
#include <vector>

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "renderers/frame_params.h"
#include "renderers/renderer.h"
#include "renderers/shading/cpu_shading.h"

namespace sdfbench {

// The pixel loop's output: what a tile's shader stores for pixel i.
struct CpuFrameTarget {
  FrameImages& img;
  std::vector<uint32_t>& rays;
  std::vector<uint32_t>& counts;  // COUNTER_KINDS per pixel, instrumented frames only
  bool counting;
  void store(size_t i, const glm::vec4& color, const shading::PixelAov& aov, const shading::PixelCounts& work) {
    img.color[i] = color;
    if (counting) std::copy(work.begin(), work.end(), counts.begin() + i * COUNTER_KINDS);
    img.depth[i] = aov.depth;
    img.instance_id[i] = aov.instance;
    img.primitive_id[i] = aov.prim;
    img.normal[i] = aov.normal;
    rays[i] = aov.rays;
  }
};

// The frame loop with a tile shader of the backend's: shade_tile(rows, cols, target) shades
// every pixel of the tile (blocked_range rows and cols) and stores it in the target.
template <class ShadeTile>
FrameResult render_cpu_frame_tiles(const FrameRequest& request, unsigned threads, uint32_t counter_kinds, ShadeTile shade_tile) {
  const size_t pixels = static_cast<size_t>(request.width) * request.height;
  FrameResult result;
  FrameImages& img = result.images;
  img.width = request.width;
  img.height = request.height;
  img.color.resize(pixels);
  img.depth.resize(pixels);
  img.instance_id.resize(pixels);
  img.primitive_id.resize(pixels);
  img.normal.resize(pixels);
  std::vector<uint32_t> rays(pixels);
  std::vector<uint32_t> counts(request.counters ? pixels * COUNTER_KINDS : 0);
  CpuFrameTarget target{img, rays, counts, request.counters};

  const auto start = std::chrono::steady_clock::now();
  tbb::task_arena arena(static_cast<int>(threads));
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range2d<uint32_t>(0, request.height, 16, 0, request.width, 16),
                      [&](const auto& tile) { shade_tile(tile.rows(), tile.cols(), target); });
  });
  result.wall_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  for (uint32_t r : rays) result.rays += r;
  if (request.counters) {
    result.counters = sum_counters(counts, counter_kinds);
    img.steps = pixel_steps(counts, counter_kinds);
  }
  if (!request.readback) img = FrameImages{};
  return result;
}

// The shading program over `tracer` for the tile's pixels (the CPU backends' frame).
// `inputs`: make_shading_inputs(scene, request), which a tracer may need too (sdf-cpu's footprint).
template <class Tracer>
shading::CpuShading<Tracer> cpu_program(const Tracer& tracer, const Scene& scene, const ShadingInputs& inputs) {
  return shading::CpuShading<Tracer>(tracer, inputs.frame, inputs.materials.data(), inputs.lights.data(),
                                     scene.texels.empty() ? nullptr : scene.texels.data(), inputs.implicit_objects.data(),
                                     inputs.implicit_nodes.data());
}

template <class Tracer>
FrameResult render_cpu_frame(const Tracer& tracer, const Scene& scene, const ShadingInputs& inputs,
                             const FrameRequest& request, unsigned threads, uint32_t counter_kinds) {
  return render_cpu_frame_tiles(request, threads, counter_kinds, [&](const auto& rows, const auto& cols, CpuFrameTarget& target) {
    shading::CpuShading<Tracer> program = cpu_program(tracer, scene, inputs);
    for (uint32_t y = rows.begin(); y < rows.end(); ++y)
      for (uint32_t x = cols.begin(); x < cols.end(); ++x) {
        shading::PixelAov aov;
        shading::PixelCounts work{};
        const glm::vec4 color = program.shade_pixel(glm::uvec2(x, y), aov, request.counters ? &work : nullptr);
        target.store(static_cast<size_t>(y) * request.width + x, color, aov, work);
      }
  });
}

}  // namespace sdfbench
