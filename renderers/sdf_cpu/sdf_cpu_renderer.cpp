#include <iostream>
#include <memory>

#include "renderers/backend.h"
#include "renderers/cpu_frame.h"
#include "renderers/frame_params.h"
#include "renderers/renderer.h"
#include "renderers/sdf/scene_hash.h"
#include "renderers/sdf/sdf_cache.h"
#include "renderers/sdf/sdf_params.h"
#include "renderers/sdf/sphere_tracer.h"
#include "util/cpu_info.h"
#include "util/error.h"

namespace sdfbench {

// The CPU reference for the SDF backends: the scene hash (+ octree) and mesh distance grids,
// sphere-traced on the CPU with the GPU's parameters. Slow; for checking the structures.
class SdfCpuRenderer : public Renderer {
 public:
  explicit SdfCpuRenderer(const BackendOptions& options);
  std::string name() const override { return "sdf-cpu"; }
  std::string device_name() const override;
  std::string driver_name() const override { return "sdfbench CPU sphere tracer"; }
  void prepare(const Scene& scene) override;
  FrameResult render(const FrameRequest& request) override;
  const sdf::SceneSdf& structures() const { return *sdf_; }
  std::optional<StructureStats> structure_stats() const override;

 private:
  BackendOptions options_;
  unsigned threads_;
  const Scene* scene_ = nullptr;
  std::unique_ptr<sdf::SceneSdf> sdf_;
  std::unique_ptr<sdf::SphereTracer> tracer_;
};

SdfCpuRenderer::SdfCpuRenderer(const BackendOptions& options) : options_(options), threads_(cpu_thread_count(options)) {
  sdf::scene_hash_params(options.params);  // validated before the scene is loaded
}

std::string SdfCpuRenderer::device_name() const { return cpu_model() + " (" + std::to_string(threads_) + " threads)"; }

void SdfCpuRenderer::prepare(const Scene& scene) {
  scene_ = &scene;
  tracer_.reset();
  sdf_ = std::make_unique<sdf::SceneSdf>(sdf::obtain_scene_sdf(scene, sdf::mesh_grid_params(options_.params),
                                                               sdf::scene_hash_params(options_.params), options_.cache, std::cerr));
  tracer_ = std::make_unique<sdf::SphereTracer>(scene, *sdf_, sdf::trace_params(options_.params));
}

std::optional<StructureStats> SdfCpuRenderer::structure_stats() const {
  if (!sdf_) return std::nullopt;
  return StructureStats{sdf::build_ms(*sdf_), sdf::bytes(*sdf_)};
}

FrameResult SdfCpuRenderer::render(const FrameRequest& request) {
  if (!tracer_) throw InternalError("render before prepare");
  const ShadingInputs inputs = make_shading_inputs(*scene_, request);
  tracer_->set_frame(inputs.frame);
  return render_cpu_frame(*tracer_, *scene_, inputs, request, threads_, kSdfCounters);
}

BackendInfo sdf_cpu_backend() {
  BackendInfo info;
  info.name = "sdf-cpu";
  info.kind = BackendKind::SdfCpu;
  info.summary = "the SDF reference on the CPU: sdf-octree's structure and tracing, for checking the kernels";
  info.vulkan = false;
  std::vector<ParamSpec> params = sdf::sdf_params({"hash_cell", "octree_depth", "octree_min_objects", "octree_min_size", "lists",
                                                   "mesh_cell", "cells_per_extent", "fixed_grid", "hit", "max_steps",
                                                   "hit_epsilon", "hit_footprint", "over_relax", "max_structure_mb"},
                                                  {"exact", "thesis"});
  info.params = std::move(params);
  info.counters = info.steps = info.stores_structure = info.scene_hash = true;
  info.in_table = false;  // slow; for checking the structures
  info.create = factory<SdfCpuRenderer>();
  return info;
}

}  // namespace sdfbench
