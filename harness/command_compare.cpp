// `sdfbench compare`: render one scene with several backends and check their images agree.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "harness/cli_common.h"
#include "harness/commands.h"
#include "harness/image_agreement.h"
#include "harness/image_output.h"
#include "harness/list_option.h"
#include "harness/output_paths.h"
#include "scenes/scene_source.h"
#include "util/error.h"

namespace sdfbench {
namespace {

struct CompareArgs {
  std::string scene, backends, reference = "embree", mode = "primary", size, out_dir;
  std::optional<uint32_t> max_depth;
  AgreementThresholds thresholds;
  BackendOptions backend_options;
};

// `instance_voxels` (nullable): a sampled field's voxel per instance (StructureStats).
FrameImages render_once(const std::string& backend, const BackendOptions& options, const Scene& scene,
                        const FrameRequest& request, std::string& device, std::vector<float>* instance_voxels = nullptr) {
  std::unique_ptr<Renderer> renderer = create_renderer(backend, options);
  renderer->prepare(scene);
  device = renderer->device_name();
  if (const auto stats = renderer->structure_stats(); stats && instance_voxels) *instance_voxels = stats->instance_voxels;
  FrameResult frame = renderer->render(request);
  if (const std::string error = truncation_error(backend, frame); !error.empty()) throw Error(error);
  if (const uint32_t messages = renderer->validation_messages(); messages > 0)
    throw Error(backend + ": " + std::to_string(messages) + " Vulkan validation message(s) (printed above)");
  return std::move(frame.images);
}

void run_compare(const CompareArgs& args) {
  const RenderMode mode = parse_mode_option(args.mode);
  const std::vector<std::string> backends = split_list(args.backends, "--backends");
  for (const std::string& b : backends) check_backend_name(b);
  check_backend_name(args.reference);
  std::vector<std::string> run = backends;
  if (std::find(run.begin(), run.end(), args.reference) == run.end()) run.push_back(args.reference);
  check_options_taken(args.backend_options, run);
  if (std::none_of(backends.begin(), backends.end(),
                   [&](const std::string& b) { return !is_reference_configuration(b, args.reference, args.backend_options); }))
    throw Error("--backends '" + args.backends + "' lists only the reference (" + args.reference +
                "): nothing to compare; add another backend, e.g. " + args.reference + ",tri-aabb");
  if (!args.out_dir.empty() && !std::filesystem::is_directory(args.out_dir))
    throw Error("--out-dir '" + args.out_dir + "' is not a directory");

  const Scene scene = load_scene(args.scene);
  if (!args.out_dir.empty()) {  // DIR/<backend>.png may be one of the scene's textures
    std::vector<NamedPath> images;
    images.push_back({"--out-dir image", std::filesystem::path(args.out_dir) / (args.reference + ".png")});
    for (const std::string& b : backends)
      if (b != args.reference) images.push_back({"--out-dir image", std::filesystem::path(args.out_dir) / (b + ".png")});
    check_distinct_outputs(images, scene_inputs(scene));
  }
  const ImageSize size = frame_size(args.size, scene);
  const FrameRequest request{size.width, size.height, mode, true, args.max_depth};
  std::cout << "scene      " << describe_scene(scene) << "\n"
            << "frame      " << describe_mode(request, scene) << ", " << size.width << "x" << size.height << "\n"
            << "reference  " << args.reference << "\n\n";

  std::string device;
  const FrameImages reference =
      render_once(args.reference, reference_options(args.reference, args.backend_options), scene, request, device);
  if (!args.out_dir.empty()) write_color_image(reference, std::filesystem::path(args.out_dir) / (args.reference + ".png"));

  std::printf("%-12s %8s %8s %11s %10s %9s %9s %8s  %s\n", "backend", "hit %", "id %", "depth p99", "mean err",
              "RMS", "PSNR dB", ">0.05 %", "result");
  int failures = 0;
  for (const std::string& backend : backends) {
    if (is_reference_configuration(backend, args.reference, args.backend_options)) continue;
    std::vector<float> voxels;
    const FrameImages images = render_once(backend, args.backend_options, scene, request, device, &voxels);
    if (!args.out_dir.empty()) write_color_image(images, std::filesystem::path(args.out_dir) / (backend + ".png"));
    const Agreement g = compare_frames(images, reference, voxels);
    const std::string failed = check_thresholds(g, args.thresholds);
    failures += !failed.empty();
    std::printf("%-12s %8.3f %8.3f %11.3g %10.3g %9.3g %9.2f %8.3f  %s\n", backend.c_str(), g.hit_percent, g.id_percent,
                g.depth_p99, g.mean_error, g.rms_error, g.psnr, g.over_threshold_percent,
                failed.empty() ? "ok" : ("FAIL: " + failed).c_str());
    if (g.depth_p99_voxels) std::printf("%-12s depth error p99: %.3g voxels of its sampled field\n", "", *g.depth_p99_voxels);
    std::fflush(stdout);
  }
  const AgreementThresholds& t = args.thresholds;
  std::printf("\nthresholds: hit >= %g %%, id >= %g %%, depth p99 <= %g, PSNR >= %g dB\n", t.min_hit_percent,
              t.min_id_percent, t.max_depth_p99, t.min_psnr);
  if (failures > 0) {
    std::cerr << "sdfbench: " << failures << " backend(s) disagree with " << args.reference << "\n";
    throw CommandFailed{2};
  }
}

}  // namespace

void register_compare_command(CLI::App& app) {
  auto args = std::make_shared<CompareArgs>();
  CLI::App* cmd = app.add_subcommand(
      "compare", "Render a scene with several backends and compare each with a reference (exit 2 when they disagree)");
  cmd->add_option("--scene", args->scene, "scene descriptor (.json) or generator, e.g. thesis:bunny:100")->required();
  cmd->add_option("--backends", args->backends, "comma-separated backends, e.g. embree,tri-aabb")->required();
  cmd->add_option("--reference", args->reference, "backend the others are compared with")->capture_default_str();
  add_mode_options(*cmd, args->mode, args->max_depth);
  cmd->add_option("--size", args->size, "WIDTHxHEIGHT (default: the scene's render size)");
  cmd->add_option("--out-dir", args->out_dir, "also write each backend's image as DIR/<backend>.png");
  cmd->add_option("--min-hit", args->thresholds.min_hit_percent, "minimum hit-mask agreement, % of pixels")
      ->capture_default_str()->check(number_in(0.0, 100.0));
  cmd->add_option("--min-id", args->thresholds.min_id_percent,
                  "minimum instance-id agreement, % of pixels where either image hit an instance")
      ->capture_default_str()->check(number_in(0.0, 100.0));
  cmd->add_option("--max-id-mismatches", args->thresholds.max_id_mismatches,
                  "--min-id passes anyway when at most this many pixels differ (tiny objects)")
      ->capture_default_str();
  cmd->add_option("--max-depth-error", args->thresholds.max_depth_p99,
                  "maximum 99th percentile of relative depth error where both hit the same instance")
      ->capture_default_str()->check(number_in(0.0, 1e30));
  cmd->add_option("--min-psnr", args->thresholds.min_psnr, "minimum PSNR of the shaded image, dB")->capture_default_str()
      ->check(number_in(-1000.0, 1000.0));
  add_backend_options(*cmd, args->backend_options);
  cmd->callback([args] { run_compare(*args); });
}

}  // namespace sdfbench
