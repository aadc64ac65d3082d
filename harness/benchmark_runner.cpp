#include "harness/benchmark_runner.h"

#include <cctype>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <set>
#include <thread>

#include "harness/image_output.h"
#include "harness/system_info.h"
#include "harness/timing_stats.h"
#include "renderers/embree/embree_api.h"
#include "scenes/overlap_layout.h"
#include "scenes/scene_source.h"
#include "util/cpu_info.h"
#include "util/machine_load.h"

namespace sdfbench {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// "bunny" for a thesis scene, else its distinct meshes joined with '+'; triangles of those meshes.
std::pair<std::string, size_t> mesh_summary(const Scene& scene) {
  std::set<uint32_t> used;
  for (const Instance& i : scene.instances) used.insert(i.mesh);
  std::string names;
  size_t triangles = 0;
  for (uint32_t m : used) {
    names += (names.empty() ? "" : "+") + scene.meshes[m].name;
    triangles += scene.meshes[m].triangle_count();
  }
  return {names, triangles};
}

// Letters, digits, '.', '-' and '_' of `text`, the rest as '_', at most 60 characters: a file name part.
std::string file_name_part(const std::string& text) {
  std::string part;
  for (char c : text.substr(0, 60)) part += std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '_' ? c : '_';
  return part;
}

// `path` relative to `base` (both as the process reaches them), or as it is without a base.
std::string relative_to(const std::filesystem::path& path, const std::filesystem::path& base) {
  if (base.empty()) return path.string();
  return std::filesystem::weakly_canonical(path).lexically_relative(std::filesystem::weakly_canonical(base)).string();
}

}  // namespace

Measurement configuration_fields(const BenchConfig& config, size_t run_index, const BenchSettings& settings) {
  Measurement m;
  m.run_index = run_index;
  m.table = config.table;
  m.scene = config.scene;
  m.backend = config.backend;
  m.mode = to_string(config.mode);
  m.max_depth = config.max_depth;
  m.width = config.size.width;
  m.height = config.size.height;
  const BackendInfo& backend = backend_info(config.backend);
  m.backend_params = recorded_params(backend, resolve_params(backend, config.options.params));
  if (backend.stores_structure) {
    m.cache = config.options.cache.path;
    if (!m.cache.empty()) m.on_bad_cache = config.options.cache.on_bad == BadCachePolicy::Rebuild ? "rebuild" : "refuse";
  }
  m.requested_frames = settings.frames;
  m.warmup = settings.warmup;
  m.budget_s = settings.budget_s;
  m.check_size = std::to_string(settings.check_size.width) + "x" + std::to_string(settings.check_size.height);
  m.reference = settings.reference;
  m.requested_device = config.options.device;
  m.whitted_passes = !config.options.whitted_passes ? "auto" : *config.options.whitted_passes ? "on" : "off";
  m.validate = config.options.validation;
  m.threads = cpu_thread_count(config.options);
  m.embree = embree::version();  // the reference's library and the bvh backend's builder, also on ERROR rows
  return m;
}

const Scene& BenchmarkRunner::scene(const std::string& spec) {
  if (!scene_ || scene_spec_ != spec) {
    scene_.reset();
    references_.clear();
    scene_ = std::make_unique<Scene>(load_scene(spec));
    scene_spec_ = spec;
    scene_overlap_ = scene_->instances.empty() ? std::nullopt : std::optional<double>(measured_overlap(*scene_));
  }
  return *scene_;
}

const FrameImages& BenchmarkRunner::reference(const BenchConfig& config) {
  const std::string key = to_string(config.mode) + " " + std::to_string(config.max_depth);
  auto it = references_.find(key);
  if (it != references_.end()) return it->second;
  std::unique_ptr<Renderer> renderer = create_renderer(settings_.reference, reference_options(settings_.reference, config.options));
  renderer->prepare(scene(config.scene));
  FrameRequest request{settings_.check_size.width, settings_.check_size.height, config.mode, true, config.max_depth};
  return references_.emplace(key, std::move(renderer->render(request).images)).first->second;
}

CheckedFrame BenchmarkRunner::check_frame(const BenchConfig& config) {
  std::unique_ptr<Renderer> renderer = create_renderer(config.backend, config.options);
  renderer->prepare(scene(config.scene));
  const FrameRequest check{settings_.check_size.width, settings_.check_size.height, config.mode, true, config.max_depth};
  CheckedFrame out;
  out.frame = std::move(renderer->render(check).images);
  out.reference = reference(config);
  const std::optional<StructureStats> stats = renderer->structure_stats();
  out.agreement = compare_frames(out.frame, out.reference, stats ? stats->instance_voxels : std::vector<float>{});
  return out;
}

void BenchmarkRunner::keep_images(const BenchConfig& config, size_t run_index, const FrameImages& frame, Measurement& m) {
  char index[16];
  std::snprintf(index, sizeof index, "%04zu", run_index);
  const std::string stem = run_id_.substr(0, 8) + "-" + index + "-" + file_name_part(config.scene) + "-" +
                           file_name_part(config.backend) + "-" + to_string(config.mode);
  const std::filesystem::path dir = settings_.keep_images;
  const FrameImages& ref = is_reference_configuration(config.backend, settings_.reference, config.options) ? frame : reference(config);
  write_color_image(frame, dir / (stem + ".frame.png"));
  write_color_image(ref, dir / (stem + ".reference.png"));
  write_difference_map(frame, ref, dir / (stem + ".diff.png"));
  m.frame_image = relative_to(dir / (stem + ".frame.png"), settings_.images_base);
  m.reference_image = relative_to(dir / (stem + ".reference.png"), settings_.images_base);
  m.diff_image = relative_to(dir / (stem + ".diff.png"), settings_.images_base);
}

Measurement BenchmarkRunner::run(const BenchConfig& config, size_t run_index) {
  const Scene& s = scene(config.scene);
  Measurement m = configuration_fields(config, run_index, settings_);
  std::tie(m.mesh, m.triangles) = mesh_summary(s);
  m.objects = s.instances.size();
  m.overlap = scene_overlap_;

  std::unique_ptr<Renderer> renderer = create_renderer(config.backend, config.options);
  const Clock::time_point prepare_start = Clock::now();
  renderer->prepare(s);
  m.prepare_ms = seconds_since(prepare_start) * 1e3;
  const std::optional<StructureStats> stats = renderer->structure_stats();
  if (stats) {
    m.backend_resolved = stats->resolved;
    m.build_ms = stats->build_ms;
    m.structure_bytes = static_cast<double>(stats->bytes);
    m.tree_sah = stats->sah;
    m.tree_epo = stats->epo;
    if (stats->nodes) m.tree_nodes = static_cast<double>(*stats->nodes);
  }

  // Frames until the budget would be exceeded by one more (estimated by the last frame's wall time).
  const Clock::time_point start = Clock::now();
  const double budget = settings_.budget_s;
  auto room_for_another = [&](double last_ms) { return seconds_since(start) + last_ms / 1e3 <= budget; };
  FrameRequest request{config.size.width, config.size.height, config.mode, false, config.max_depth};
  std::vector<FrameResult> timed;
  FrameResult last;
  bool rendered = false;
  for (unsigned i = 0; i < settings_.warmup && (!rendered || room_for_another(last.wall_ms)); ++i) {
    last = renderer->render(request);
    rendered = true;
  }
  const LoadMeter load_meter;
  while (timed.size() < settings_.frames && (!rendered || room_for_another(last.wall_ms))) {
    last = renderer->render(request);
    rendered = true;
    timed.push_back(last);
  }
  if (const std::optional<MachineLoad> load = load_meter.stop()) {
    m.load_avg = load->load_avg;
    m.cpu_steal_pct = load->steal_pct;
    m.cpu_other_pct = load->other_pct;
    m.busy = load->busy(std::max(1u, std::thread::hardware_concurrency()));
    if (*m.busy && !warned_busy_) {
      warned_busy_ = true;
      std::cerr << "sdfbench: warning: the machine was busy while rows were timed (load average " << load->load_avg
                << ", steal " << load->steal_pct << " %, other processes " << load->other_pct
                << " % of the CPUs); such rows are flagged (busy column, ‡ in the markdown)\n";
    }
  }
  if (timed.empty()) timed.push_back(last);  // the budget allowed only the warm-up frame: report it, flagged
  m.budget_cut = timed.size() < settings_.frames;
  const FrameTimingSummary t = summarize_frames(timed);
  m.frames = static_cast<unsigned>(timed.size());
  m.clock = t.clock;
  m.ms_median = t.median_ms;
  m.ms_min = t.min_ms;
  m.ms_max = t.max_ms;
  m.ms_wall_median = t.wall_median_ms;
  m.fps = t.fps;
  m.mrays_per_s = t.mrays_per_s;
  m.rays_per_pixel = static_cast<double>(timed.back().rays) / (static_cast<double>(m.width) * m.height);

  // Agreement and work counters at the check size: one untimed, instrumented frame (the
  // counters change no pixel).
  const FrameRequest check{settings_.check_size.width, settings_.check_size.height, config.mode, true, config.max_depth, true};
  const FrameResult checked = renderer->render(check);
  for (uint32_t k = 0; k < COUNTER_KINDS; ++k)
    if (checked.counters[k] && checked.rays > 0)
      m.per_ray[k] = static_cast<double>(*checked.counters[k]) / static_cast<double>(checked.rays);
  if (is_reference_configuration(config.backend, settings_.reference, config.options)) {
    m.agreement = "reference";
  } else {
    const Agreement g = compare_frames(checked.images, reference(config), stats ? stats->instance_voxels : std::vector<float>{});
    m.hit_agreement = g.hit_percent;
    m.id_agreement = g.id_percent;
    m.depth_p99 = g.depth_p99;
    m.depth_p99_voxels = g.depth_p99_voxels;
    m.psnr = g.psnr;
    const std::string failed = check_thresholds(g, settings_.thresholds);
    m.agreement = failed.empty() ? "ok" : "DISAGREE: " + failed;
  }
  // Cut short by lavapipe's loop limit, the images and times are invalid whatever they agree with.
  if (timed.back().truncated_pixels > 0)
    m.agreement = "TRUNCATED: " + std::to_string(timed.back().truncated_pixels) + " pixels";
  else if (checked.truncated_pixels > 0)
    m.agreement = "TRUNCATED: " + std::to_string(checked.truncated_pixels) + " pixels at the check size";
  if (const uint32_t messages = renderer->validation_messages(); messages > 0)
    m.agreement += " (" + std::to_string(messages) + " validation messages)";

  if (!settings_.keep_images.empty()) keep_images(config, run_index, checked.images, m);

  m.device = renderer->device_name();
  m.driver = renderer->driver_name();
  m.cpu = cpu_model();
  m.commit = git_commit();
  return m;
}

}  // namespace sdfbench
