#pragma once
// Runs one benchmark configuration the way docs/design.md, "Measuring", says: prepare (timed),
// warm-up frames, N timed frames inside a time budget, then the image-agreement check against
// the reference backend at a check resolution. Scenes and reference images are cached across
// configurations of one run.
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "harness/cli_common.h"
#include "harness/image_agreement.h"
#include "harness/measurement.h"
#include "renderers/renderer.h"

namespace sdfbench {

struct BenchConfig {
  std::string table;  // thesis table id, "sweep", or empty
  std::string scene;  // descriptor path or generator spec
  std::string backend;
  RenderMode mode = RenderMode::Primary;
  ImageSize size;
  unsigned max_depth = 4;  // whitted recursion limit
  BackendOptions options;
};

struct BenchSettings {
  unsigned warmup = 1, frames = 5;
  double budget_s = 300;  // per configuration, from the first warm-up frame on
  ImageSize check_size{160, 90};
  std::string reference = "embree";
  AgreementThresholds thresholds;
  // --keep-images: each row's check images go to this folder (empty: none kept), their paths in
  // the row relative to images_base (the CSV's folder; empty: as written)
  std::filesystem::path keep_images, images_base;
};

// The configuration columns of a row, every key column (measurement.h) included, from the
// configuration and the run's settings alone (no scene loaded, nothing run): what resume and
// error rows use, and what run() starts from.
Measurement configuration_fields(const BenchConfig& config, size_t run_index, const BenchSettings& settings);

// A configuration's check frame alone, nothing timed (`report --render-missing`).
struct CheckedFrame {
  FrameImages frame, reference;
  Agreement agreement;
};

class BenchmarkRunner {
 public:
  explicit BenchmarkRunner(BenchSettings settings) : settings_(std::move(settings)) {}
  Measurement run(const BenchConfig& config, size_t run_index);
  CheckedFrame check_frame(const BenchConfig& config);
  const BenchSettings& settings() const { return settings_; }
  // The run's id (plan_run_id) begins every kept image's name, so two runs keep theirs apart.
  void set_run_id(std::string run_id) { run_id_ = std::move(run_id); }

 private:
  const Scene& scene(const std::string& spec);
  const FrameImages& reference(const BenchConfig& config);

  BenchSettings settings_;
  std::string scene_spec_;  // one scene at a time: a 1000-instance scene is worth keeping, not ten
  std::unique_ptr<Scene> scene_;
  std::optional<double> scene_overlap_;  // measured_overlap of scene_, once per scene (every row records it)
  std::map<std::string, FrameImages> references_;  // by scene + mode, for the current scene
  void keep_images(const BenchConfig& config, size_t run_index, const FrameImages& frame, Measurement& m);

  std::string run_id_;
  bool warned_busy_ = false;  // the busy-machine warning is said once per run
};

}  // namespace sdfbench
