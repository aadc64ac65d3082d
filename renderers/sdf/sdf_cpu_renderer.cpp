#include "renderers/sdf/sdf_cpu_renderer.h"

#include <iostream>

#include "util/cpu_info.h"
#include "renderers/cpu_frame.h"
#include "renderers/frame_params.h"
#include "util/error.h"

namespace sdfbench {

SdfCpuRenderer::SdfCpuRenderer(const BackendOptions& options) : options_(options), threads_(cpu_thread_count(options)) {
  if (options.tracing.cell_bound || options.tracing.storage_tables)
    throw Error(std::string("sdf-cpu: ") + (options.tracing.cell_bound ? "--cell-bound" : "--storage-tables") +
                " is an option of the Vulkan SDF kernels (sdf-hash, sdf-octree)");
  sdf::validate(options.scene_hash);
  sdf::check_exact_field_hit(options.tracing.hit, "sdf-cpu");
}

std::string SdfCpuRenderer::device_name() const { return cpu_model() + " (" + std::to_string(threads_) + " threads)"; }

void SdfCpuRenderer::prepare(const Scene& scene) {
  scene_ = &scene;
  tracer_.reset();
  sdf_ = std::make_unique<sdf::SceneSdf>(sdf::obtain_scene_sdf(scene, options_.mesh_grid,
                                                               scene_hash_params_for(name(), options_), options_.cache, std::cerr));
  tracer_ = std::make_unique<sdf::SphereTracer>(scene, *sdf_, options_.tracing);
}

std::optional<StructureStats> SdfCpuRenderer::structure_stats() const {
  if (!sdf_) return std::nullopt;
  return StructureStats{sdf::build_ms(*sdf_), sdf::bytes(*sdf_)};
}

FrameResult SdfCpuRenderer::render(const FrameRequest& request) {
  if (!tracer_) throw Error("internal: render before prepare");
  const ShadingInputs inputs = make_shading_inputs(*scene_, request);
  tracer_->set_frame(inputs.frame);
  return render_cpu_frame(*tracer_, *scene_, inputs, request, threads_, kSdfCounters);
}

}  // namespace sdfbench
