#include "renderers/sdf_bricks/brick_field_tables.h"

#include <cmath>

#include "renderers/sdf_vk/sdf_gpu_tables.h"

namespace sdfbench {
namespace {

// --brick-fetch auto on a CPU device (lavapipe): measured on thesis:bunny:1000 (results/lavapipe/).
constexpr bool kLavapipeSampler = false;

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

std::vector<ParamSpec> brick_field_param_specs() {
  // Defaults from the measurements in results/lavapipe/ (docs/backends.md, "sdf-bricks", "sdf-global").
  const std::string group = "sampled fields (sdf-bricks, sdf-global)";
  return {
      {"sdf_format", ParamKind::Choice, "f32", "stored field values: f32, f16 or u8 (a band-relative UNORM)", group,
       {"f32", "f16", "u8"}},
      {"brick_band", ParamKind::Integer, "4", "bricks within this many voxels of the surface are stored", group, {}, 1, 16},
      {"brick_fetch", ParamKind::Choice, "auto",
       "texel: 8 texel-buffer fetches and the trilinear in the kernel; sampler: the atlas as a 3D image the sampler "
       "filters; auto: by device, from the measurement (docs/backends.md, \"sdf-bricks\"); the row's backend_resolved says which",
       group, {"auto", "texel", "sampler"}},
  };
}

sdf::SdfFormat sdf_format_param(const BackendParams& params) {
  const std::string& format = params.text("sdf_format");
  return format == "f16" ? sdf::SdfFormat::f16 : format == "u8" ? sdf::SdfFormat::u8 : sdf::SdfFormat::f32;
}

std::string brick_kernel_defines(const BackendOptions& options, bool sampler) {
  std::string defines = sampler ? "#define BRICK_SAMPLER 1\n" : "";
  if (options.params.text("hit") == "field") defines += "#define BRICK_HIT_FIELD 1\n";
  if (options.params.text("sdf_format") == "u8") defines += "#define BRICK_U8 1\n";
  if (options.params.flag("storage_tables")) defines += "#define SDF_STORAGE_TABLES 1\n";
  return defines;
}

BrickFieldTables::BrickFieldTables(const VulkanContext& context, const BrickGpuArrays& arrays, bool sampler,
                                   shading::SdfParams& params, const char* hint)
    : sampler_(sampler) {
  records_ = upload_table(context, arrays.records, VK_FORMAT_R32G32B32A32_UINT, 16, false, "brick field records", hint);
  slots_ = upload_table(context, arrays.slots, VK_FORMAT_R32_UINT, 4, false, "brick indirection", hint);
  const VkFormat format = atlas_format(arrays.format);
  const size_t sample_bytes = sdf::bytes_per_sample(arrays.format);
  if (sampler_) {
    const BrickAtlasImage image = arrange_atlas_image(arrays, context.properties().limits.maxImageDimension3D);
    params.atlas_bricks = glm::uvec4(image.bricks.x, image.bricks.y, 0u, 0u);
    params.atlas_inverse_size = glm::vec4(1.0f / glm::vec3(image.extent), 0.0f);
    // The sampler's weights have subTexelPrecisionBits: its sample is the exact trilinear at a point
    // up to sqrt(3) 2^-bits voxels away (twice that, for the slack's own change over that way).
    params.options.z = 2.0f * std::sqrt(3.0f) * std::ldexp(1.0f, -int(context.properties().limits.subTexelPrecisionBits));
    // ... and its result has a precision of its own: a UNORM8 image may be filtered in 8-bit fixed
    // point, three rounds of lerps each off by up to a step (lavapipe's is: 1.35 steps from the exact
    // trilinear at most over 24685 points, renderers/sdf_bricks/brick_sampler_probe_test.cpp, where 1/1024 of the
    // band failed), so u8 allows three steps of 2 band / 255; the float formats 1/1024 of the band.
    params.options.w = arrays.format == sdf::SdfFormat::u8 ? 6.0f / 255.0f : 1.0f / 1024.0f;
    image_ = GpuImage3D(context, image.extent, format, sample_bytes, image.texels.data(), "brick atlas");
  } else {
    atlas_ = upload_table(context, arrays.atlas, format, sample_bytes, false, "brick atlas", hint);
  }
  coarse_ = upload_table(context, arrays.coarse, VK_FORMAT_R32_SFLOAT, 4, false, "brick coarse level", hint);
}

void BrickFieldTables::add_bindings(std::vector<KernelBinding>& bindings) const {
  const VkDescriptorType texel = VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
  bindings.insert(bindings.end(), {{18, texel, &records_}, {19, texel, &slots_}, {21, texel, &coarse_}});
  if (sampler_) {
    KernelBinding atlas{20, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER};
    atlas.image = &image_;
    bindings.push_back(atlas);
  } else {
    bindings.push_back({20, texel, &atlas_});
  }
}

}  // namespace sdfbench
