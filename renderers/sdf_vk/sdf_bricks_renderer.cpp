#include "renderers/sdf_vk/sdf_bricks_renderer.h"

#include <algorithm>
#include <cmath>
#include <iostream>

#include "renderers/sdf_vk/brick_gpu_arrays.h"
#include "renderers/sdf_vk/sdf_gpu_arrays.h"
#include "util/error.h"

namespace sdfbench {
namespace {

// --hit field: rays leave a field hit from this many of the scene's largest voxels off it (the
// hit lies within a fraction of a voxel, on either side).
constexpr float kFieldHitOffsetVoxels = 2.0f;

// --brick-fetch auto on a CPU device (lavapipe): measured on thesis:bunny:1000 (results/lavapipe/).
constexpr bool kLavapipeSampler = false;

std::string kernel_defines(const BackendOptions& options, bool sampler) {
  std::string defines = sampler ? "#define BRICK_SAMPLER 1\n" : "";
  if (options.params.get("brick_trace") == "min") defines += "#define BRICK_TRACE_MIN 1\n";
  if (options.tracing.hit == sdf::HitMode::field) defines += "#define BRICK_HIT_FIELD 1\n";
  if (options.params.get("sdf_format") == "u8") defines += "#define BRICK_U8 1\n";
  if (options.tracing.storage_tables) defines += "#define SDF_STORAGE_TABLES 1\n";
  return defines + options.kernel_defines;
}

VkFormat atlas_format(sdf::SdfFormat format) {
  switch (format) {
    case sdf::SdfFormat::f32: return VK_FORMAT_R32_SFLOAT;
    case sdf::SdfFormat::f16: return VK_FORMAT_R16_SFLOAT;
    case sdf::SdfFormat::u8: return VK_FORMAT_R8_UNORM;
  }
  return VK_FORMAT_R32_SFLOAT;
}

}  // namespace

bool use_sampler(const std::string& brick_fetch, const VulkanDeviceInfo& device) {
  if (brick_fetch != "auto") return brick_fetch == "sampler";
  return device.type != "cpu" || kLavapipeSampler;
}

sdf::BrickFieldParams brick_field_params(const BackendParams& params, uint64_t max_bytes) {
  sdf::BrickFieldParams p;
  p.voxels = static_cast<uint32_t>(params.integer("voxels"));
  p.band = static_cast<uint32_t>(params.integer("brick_band"));
  const std::string& format = params.get("sdf_format");
  p.format = format == "f16" ? sdf::SdfFormat::f16 : format == "u8" ? sdf::SdfFormat::u8 : sdf::SdfFormat::f32;
  p.max_bytes = max_bytes;
  sdf::validate(p);
  return p;
}

SdfBricksRenderer::SdfBricksRenderer(const BackendOptions& options)
    : options_(options),
      field_params_(brick_field_params(options.params, options.mesh_grid.max_bytes)),
      context_(VulkanContext::Options{options.device, options.validation}),
      sampler_(use_sampler(options.params.get("brick_fetch"), context_.info())),
      runner_(context_, compute_tile_kernels(context_, "sdf_bricks.comp", kernel_defines(options, sampler_)), kBrickCounters,
              options.whitted_passes) {
  sdf::validate(options_.scene_hash);
  sdf::check_exact_field_hit(options_.tracing.hit, name());
  if (options_.tracing.cell_bound) throw Error("--cell-bound: sdf-bricks skips empty leaves by its own walk; it has no cell bounds");
  if (options_.tracing.over_relax != 1.0f) throw Error("--over-relax: sdf-bricks steps by a bound of its field, not over-relaxed");
}

void SdfBricksRenderer::prepare(const Scene& scene) {
  SdfGpuArrays arrays;
  BrickGpuArrays bricks;
  {  // the CPU structures are freed once flattened
    const sdf::SceneSdf sdf =
        sdf::obtain_scene_sdf(scene, options_.mesh_grid, options_.scene_hash, options_.cache, std::cerr, &field_params_);
    const std::vector<sdf::BrickField>& fields = sdf.brick_fields;
    stats_ = StructureStats{sdf::build_ms(sdf), sdf::bytes(sdf), {}, std::string("brick_fetch=") + (sampler_ ? "sampler" : "texel")};
    arrays = flatten_for_gpu(scene, sdf, options_.tracing, LeafLists::overlapping_first);
    for (const Instance& instance : scene.instances)
      stats_->instance_voxels.push_back(fields[instance.mesh].voxel * instance.transform.scale);
    const float largest_voxel =
        stats_->instance_voxels.empty() ? 0.0f : *std::max_element(stats_->instance_voxels.begin(), stats_->instance_voxels.end());
    arrays.params.options.y = options_.tracing.hit == sdf::HitMode::field ? kFieldHitOffsetVoxels * largest_voxel : 0.0f;
    // The sampler's weights have subTexelPrecisionBits: its sample is the exact trilinear at a point
    // up to sqrt(3) 2^-bits voxels away (twice that, for the slack's own change over that way).
    arrays.params.options.z =
        2.0f * std::sqrt(3.0f) * std::ldexp(1.0f, -int(context_.properties().limits.subTexelPrecisionBits));
    bricks = flatten_brick_fields(fields);
  }
  const char* hint = "fewer --voxels or a narrower --brick-band need less";
  brick_records_ = upload_table(context_, bricks.records, VK_FORMAT_R32G32B32A32_UINT, 16, false, "brick field records", hint);
  brick_slots_ = upload_table(context_, bricks.slots, VK_FORMAT_R32_UINT, 4, false, "brick indirection", hint);
  if (sampler_) {
    const BrickAtlasImage image = arrange_atlas_image(bricks, context_.properties().limits.maxImageDimension3D);
    arrays.params.atlas_bricks = glm::uvec4(image.bricks.x, image.bricks.y, 0u, 0u);
    arrays.params.atlas_inverse_size = glm::vec4(1.0f / glm::vec3(image.extent), 0.0f);
    brick_image_ = GpuImage3D(context_, image.extent, atlas_format(bricks.format), sdf::bytes_per_sample(bricks.format),
                              image.texels.data(), "brick atlas");
  } else {
    brick_atlas_ = upload_table(context_, bricks.atlas, atlas_format(bricks.format), sdf::bytes_per_sample(bricks.format),
                                false, "brick atlas", hint);
  }
  brick_coarse_ = upload_table(context_, bricks.coarse, VK_FORMAT_R32_SFLOAT, 4, false, "brick coarse level", hint);
  tables_ = SdfGpuTables(context_, arrays, options_.tracing.storage_tables);  // after the atlas layout is in the params
  std::vector<KernelBinding> bindings = tables_.bindings();
  const VkDescriptorType texel = VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
  bindings.insert(bindings.end(), {{18, texel, &brick_records_}, {19, texel, &brick_slots_}, {21, texel, &brick_coarse_}});
  if (sampler_) {
    KernelBinding atlas{20, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER};
    atlas.image = &brick_image_;
    bindings.push_back(atlas);
  } else {
    bindings.push_back({20, texel, &brick_atlas_});
  }
  runner_.set_scene(scene, bindings);
}

}  // namespace sdfbench
