#include "renderers/sdf_vk/sdf_vk_renderer.h"

#include <iostream>

#include "renderers/sdf_vk/sdf_gpu_arrays.h"
#include "util/error.h"

namespace sdfbench {

SdfVkRenderer::SdfVkRenderer(std::string name, const BackendOptions& options)
    : name_(std::move(name)),
      options_(options),
      context_(VulkanContext::Options{options.device, options.validation}),
      runner_(context_, compute_tile_kernels(context_, "sdf_trace.comp",
                                        std::string(options.tracing.cell_bound ? "#define SDF_CELL_BOUND 1\n" : "") +
                                            (options.tracing.storage_tables ? "#define SDF_STORAGE_TABLES 1\n" : "") +
                                            options.kernel_defines), kSdfCounters, options.whitted_passes) {
  sdf::validate(scene_hash_params_for(name_, options_));
  sdf::check_exact_field_hit(options_.tracing.hit, name_);
}

void SdfVkRenderer::prepare(const Scene& scene) {
  const SdfGpuArrays arrays = [&] {  // the CPU structures are freed once flattened
    const sdf::SceneSdf sdf = sdf::obtain_scene_sdf(scene, options_.mesh_grid, scene_hash_params_for(name_, options_),
                                                    options_.cache, std::cerr);
    stats_ = StructureStats{sdf::build_ms(sdf), sdf::bytes(sdf)};
    return flatten_for_gpu(scene, sdf, options_.tracing);
  }();
  tables_ = SdfGpuTables(context_, arrays, options_.tracing.storage_tables);
  runner_.set_scene(scene, tables_.bindings());
}

}  // namespace sdfbench
