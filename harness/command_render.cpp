// `sdfbench render`: one backend, one scene; image, AOVs and timings.
#include <algorithm>
#include <cstdio>
#include <iostream>

#include "harness/cli_common.h"
#include "harness/commands.h"
#include "harness/image_output.h"
#include "harness/output_paths.h"
#include "harness/structure_view.h"
#include "harness/timing_stats.h"
#include "renderers/sdf/sdf_cache.h"
#include "renderers/sdf/sdf_params.h"
#include "scenes/scene_source.h"
#include "util/error.h"

namespace sdfbench {
namespace {

struct RenderArgs {
  std::string scene, backend, mode = "primary", size, out, aov, view, heatmap;
  bool counters = false;
  std::vector<uint32_t> view_cell;
  std::optional<uint32_t> max_depth;
  unsigned frames = 5, warmup = 1;
  BackendOptions backend_options;
};

// One untimed instrumented frame (after the timed ones, so their kernels stay uninstrumented):
// prints the work per ray and writes the --heatmap of steps per pixel.
void report_counters(const RenderArgs& args, Renderer& renderer, FrameRequest request) {
  request.counters = true;
  request.readback = !args.heatmap.empty();
  const FrameResult frame = renderer.render(request);
  if (const std::string error = truncation_error(args.backend, frame); !error.empty()) throw Error(error);
  const auto names = counter_names();
  std::string line;
  for (uint32_t k = 0; k < COUNTER_KINDS; ++k) {
    if (!frame.counters[k]) continue;
    char value[32];
    std::snprintf(value, sizeof value, "%.2f", static_cast<double>(*frame.counters[k]) / static_cast<double>(frame.rays));
    line += std::string(line.empty() ? "" : ", ") + names[k] + " " + value;
  }
  if (line.empty())
    std::cout << "counters n/a: " << args.backend << " does not expose its traversal work (Embree's and the driver's are opaque)\n";
  else
    std::cout << "counters per ray (" << frame.rays << " rays, untimed instrumented frame): " << line << "\n";
  if (!args.heatmap.empty()) {
    const HeatmapRange range = write_heatmap(frame.images.steps, request.width, request.height, args.heatmap);
    std::cout << "wrote    " << args.heatmap << " (sphere-tracing steps per pixel, all its rays: 0 dark violet .. "
              << range.top << " yellow = 99th percentile and above; max " << range.max << ")\n";
  }
}

// The frame with the scene hash (or one hash cell's octree) drawn over it, as thesis figures
// 6.6-6.7; the structures are the backend's (sdf-hash: cell 1 unless --hash-cell).
FrameImages structure_view(const RenderArgs& args, const Scene& scene, const FrameRequest& request, const FrameImages& frame) {
  const BackendParams params = resolve_params(backend_info(args.backend), args.backend_options.params);
  const sdf::SceneSdf sdf = sdf::obtain_scene_sdf(scene, sdf::mesh_grid_params(params), sdf::scene_hash_params(params),
                                                  args.backend_options.cache, std::cerr);
  const StructureView view = args.view == "hash" ? StructureView::Hash : StructureView::Octree;
  const glm::uvec3 shown = args.view_cell.empty() ? default_view_cell(frame, scene, request, sdf.hash)
                                                  : glm::uvec3(args.view_cell[0], args.view_cell[1], args.view_cell[2]);
  const sdf::SceneHash& h = sdf.hash;
  std::cout << "view     " << args.view << ": hash " << h.dims.x << "x" << h.dims.y << "x" << h.dims.z << " cells of "
            << h.cell_size;
  if (view == StructureView::Octree)
    std::cout << ", octree of cell " << shown.x << "," << shown.y << "," << shown.z << " (depth <= " << h.params.octree_depth
              << "; leaves tinted blue = shallow ... red = deepest)";
  std::cout << "\n";
  return overlay_structure(frame, scene, request, h, view, shown);
}

void run_render(const RenderArgs& args) {
  const RenderMode mode = parse_mode_option(args.mode);
  if (!args.out.empty()) check_image_path(args.out, "--out");
  if (!args.aov.empty()) check_aov_path(args.aov, "--aov");
  const BackendInfo& backend = backend_info(args.backend);
  if (!args.view.empty() && args.out.empty()) throw Error("--view draws over the --out image: give --out");
  if (!args.view.empty() && !backend.scene_hash)
    throw Error("--view draws the scene hash and its octrees: " + args.backend + " has none (backends with one: " +
                backends_with(&BackendInfo::scene_hash) + ")");
  if (!args.heatmap.empty()) {
    check_image_path(args.heatmap, "--heatmap");
    if (!backend.steps) throw Error("--heatmap maps sphere-tracing steps: " + args.backend + " takes none (use an sdf-* backend)");
  }
  check_options_taken(args.backend_options, {args.backend});
  const Scene scene = load_scene(args.scene);
  check_distinct_outputs({{"--out", args.out}, {"--aov", args.aov}, {"--heatmap", args.heatmap},
                          {"--cache", args.backend_options.cache.path}},
                         scene_inputs(scene));
  const ImageSize size = frame_size(args.size, scene);

  std::unique_ptr<Renderer> renderer = create_renderer(args.backend, args.backend_options);
  renderer->prepare(scene);
  FrameRequest request{size.width, size.height, mode, false, args.max_depth};
  std::cout << "scene    " << describe_scene(scene) << "\n"
            << "backend  " << renderer->name() << " on " << renderer->device_name() << " [" << renderer->driver_name()
            << "]\n"
            << "params   " << describe_params(backend, args.backend_options.params) << "\n"
            << "frame    " << describe_mode(request, scene) << ", " << size.width << "x" << size.height << ", "
            << args.warmup << " warm-up + " << args.frames << " timed frames\n"
            << std::flush;

  for (unsigned i = 0; i < args.warmup; ++i) renderer->render(request);
  std::vector<FrameResult> timed;
  for (unsigned i = 0; i < args.frames; ++i) {
    request.readback = i + 1 == args.frames;  // pixels of the last frame only
    timed.push_back(renderer->render(request));
    if (timed.back().wall_ms > 1000.0)
      std::cerr << "  frame " << (i + 1) << "/" << args.frames << ": " << timed.back().wall_ms << " ms\n";
  }
  if (const std::string error = truncation_error(args.backend, timed.back()); !error.empty()) throw Error(error);
  const FrameTimingSummary t = summarize_frames(timed);
  std::printf("time     %s median %.3f ms (min %.3f, max %.3f); wall median %.3f ms\n", t.clock.c_str(), t.median_ms,
              t.min_ms, t.max_ms, t.wall_median_ms);
  std::printf("rate     %.2f FPS, %.2f Mrays/s (%.2f rays/pixel)\n", t.fps, t.mrays_per_s,
              static_cast<double>(timed.back().rays) / (static_cast<double>(size.width) * size.height));

  if (args.counters || !args.heatmap.empty()) report_counters(args, *renderer, request);

  FrameImages images = std::move(timed.back().images);
  if (!args.view.empty()) images = structure_view(args, scene, request, images);
  if (!args.out.empty()) {
    write_color_image(images, args.out);
    std::cout << "wrote    " << args.out << "\n";
  }
  if (!args.aov.empty()) {
    write_aov_image(images, args.aov);
    std::cout << "wrote    " << args.aov << " (hit, depth, instance_id, primitive_id, N)\n";
  }
  if (const uint32_t messages = renderer->validation_messages(); messages > 0)
    throw Error(std::to_string(messages) + " Vulkan validation message(s) (printed above)");
}

}  // namespace

void register_render_command(CLI::App& app) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand("render", "Render a scene with one backend; print timings, write image and AOVs");
  cmd->add_option("--scene", args->scene, "scene descriptor (.json) or generator, e.g. thesis:bunny:100[:seed]")->required();
  cmd->add_option("--backend", args->backend, "one of " + backend_list() + " (`sdfbench backends` describes them)")->required();
  add_mode_options(*cmd, args->mode, args->max_depth);
  cmd->add_option("--size", args->size, "WIDTHxHEIGHT (default: the scene's render size)");
  cmd->add_option("--frames", args->frames, "timed frames")->capture_default_str()->check(CLI::Range(1u, 100000u));
  cmd->add_option("--warmup", args->warmup, "untimed warm-up frames")->capture_default_str()->check(CLI::Range(0u, 100000u));
  cmd->add_option("--out", args->out, "write the shaded image (.png, .exr, ...)");
  cmd->add_option("--aov", args->aov, "write the AOVs as a multi-channel .exr");
  cmd->add_option("--view", args->view, "draw the SDF structure over the --out image: hash (its cells) or octree (one cell's)")
      ->check(CLI::IsMember({"hash", "octree"}));
  cmd->add_option("--view-cell", args->view_cell, "--view octree: the hash cell X,Y,Z (default: the most refined one)")
      ->delimiter(',')->expected(3);
  cmd->add_flag("--counters", args->counters,
                "after the timed frames, render one untimed instrumented frame and print the work per ray "
                "(steps, instance/triangle distance evaluations, AABB and triangle tests)");
  cmd->add_option("--heatmap", args->heatmap,
                  "write that frame's sphere-tracing steps per pixel as a colour-map image (.png; implies --counters)");
  add_backend_options(*cmd, args->backend_options);
  cmd->callback([args] { run_render(*args); });
}

}  // namespace sdfbench
