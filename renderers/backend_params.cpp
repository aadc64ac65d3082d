#include "renderers/backend_params.h"

#include <algorithm>
#include <charconv>

#include "util/error.h"

namespace sdfbench {
namespace {

const ParamSpec& spec_of(const std::string& name) {
  for (const ParamSpec& spec : param_specs())
    if (spec.name == name) return spec;
  throw Error("internal: no backend parameter '" + name + "'");
}

}  // namespace

const std::vector<ParamSpec>& param_specs() {
  // sdf-bricks: the per-mesh brick fields (renderers/sdf/brick_field.h) and how sdf_bricks.comp
  // uses them. Defaults from the measurements in results/lavapipe/ (README, "sdf-bricks").
  static const std::vector<ParamSpec> specs = {
      {"voxels", "sdf-bricks", "128", "brick field lattice cells along each mesh's largest extent", {}, 4, 1024},
      {"sdf_format", "sdf-bricks", "f32", "stored field values: f32, f16 or u8 (a band-relative UNORM)", {"f32", "f16", "u8"}},
      {"brick_band", "sdf-bricks", "4", "bricks within this many voxels of the surface are stored", {}, 1, 16},
      {"brick_trace", "sdf-bricks", "instance",
       "instance: each listed instance traced through its own field, t clamped to the best hit (UE5); "
       "min: the thesis' per-step minimum over the leaf's instances",
       {"instance", "min"}},
      {"brick_fetch", "sdf-bricks", "auto",
       "texel: 8 texel-buffer fetches and the trilinear in the kernel; sampler: the atlas as a 3D image the sampler "
       "filters; auto: by device, from the measurement (README, \"sdf-bricks\"); the row's backend_resolved says which",
       {"auto", "texel", "sampler"}},
  };
  return specs;
}

std::string flag_of(const ParamSpec& spec) {
  std::string flag = "--" + spec.name;
  std::replace(flag.begin(), flag.end(), '_', '-');
  return flag;
}

std::string check_param_value(const ParamSpec& spec, const std::string& value) {
  if (!spec.choices.empty()) {
    if (std::find(spec.choices.begin(), spec.choices.end(), value) != spec.choices.end()) return "";
    std::string known;
    for (const std::string& c : spec.choices) known += (known.empty() ? "" : ", ") + c;
    return "expected one of " + known + ", got '" + value + "'";
  }
  int64_t v = 0;
  const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), v);
  if (value.empty() || ec != std::errc() || end != value.data() + value.size() || v < spec.lo || v > spec.hi)
    return "expected an integer in [" + std::to_string(spec.lo) + ", " + std::to_string(spec.hi) + "], got '" + value + "'";
  return "";
}

void BackendParams::set(const std::string& name, const std::string& value) {
  const ParamSpec& spec = spec_of(name);
  if (const std::string why = check_param_value(spec, value); !why.empty()) throw Error(flag_of(spec) + ": " + why);
  // One spelling per value, so that the CSV key of "064" and "64" is the same configuration.
  values_[name] = spec.choices.empty() ? std::to_string(std::stoll(value)) : value;
}

const std::string& BackendParams::get(const std::string& name) const {
  const auto it = values_.find(name);
  return it != values_.end() ? it->second : spec_of(name).default_value;
}

int64_t BackendParams::integer(const std::string& name) const { return std::stoll(get(name)); }

std::string BackendParams::misplaced_for(const std::string& backend) const {
  for (const auto& [name, value] : values_)
    if (spec_of(name).family != backend) return flag_of(spec_of(name)) + " is a parameter of " + spec_of(name).family;
  return "";
}

}  // namespace sdfbench
