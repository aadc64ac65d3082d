#include "renderers/backend_params.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <sstream>

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
  // uses them; sdf-global: the scene's one field (global_field.h) in the same brick format.
  // Defaults from the measurements in results/lavapipe/ (docs/backends.md, "sdf-bricks", "sdf-global").
  const std::vector<std::string> bricks = {"sdf-bricks"}, both = {"sdf-bricks", "sdf-global"}, global = {"sdf-global"};
  static const std::vector<ParamSpec> specs = {
      {"voxels", bricks, "128", "brick field lattice cells along each mesh's largest extent", {}, 4, 1024},
      {"global_voxel", global, "auto",
       "the global field's voxel in world units; auto: the median instance's largest extent / 10 (docs/backends.md, \"sdf-global\")",
       {"auto"}, 0, 0, true},
      {"sdf_format", both, "f32", "stored field values: f32, f16 or u8 (a band-relative UNORM)", {"f32", "f16", "u8"}},
      {"brick_band", both, "4", "bricks within this many voxels of the surface are stored", {}, 1, 16},
      {"brick_trace", bricks, "instance",
       "instance: each listed instance traced through its own field, t clamped to the best hit (UE5); "
       "min: the thesis' per-step minimum over the leaf's instances",
       {"instance", "min"}},
      {"brick_fetch", both, "auto",
       "texel: 8 texel-buffer fetches and the trilinear in the kernel; sampler: the atlas as a 3D image the sampler "
       "filters; auto: by device, from the measurement (docs/backends.md, \"sdf-bricks\"); the row's backend_resolved says which",
       {"auto", "texel", "sampler"}},
  };
  return specs;
}

std::string flag_of(const ParamSpec& spec) {
  std::string flag = "--" + spec.name;
  std::replace(flag.begin(), flag.end(), '_', '-');
  return flag;
}

bool belongs_to(const ParamSpec& spec, const std::string& backend) {
  return std::find(spec.families.begin(), spec.families.end(), backend) != spec.families.end();
}

std::string families_of(const ParamSpec& spec) {
  std::string text;
  for (const std::string& f : spec.families) text += (text.empty() ? "" : ", ") + f;
  return text;
}

std::string check_param_value(const ParamSpec& spec, const std::string& value) {
  if (std::find(spec.choices.begin(), spec.choices.end(), value) != spec.choices.end()) return "";
  std::string known;
  for (const std::string& c : spec.choices) known += (known.empty() ? "" : ", ") + c;
  if (spec.positive_real) {
    char* end = nullptr;
    const double v = value.empty() ? 0.0 : std::strtod(value.c_str(), &end);
    if (!value.empty() && end == value.c_str() + value.size() && std::isfinite(v) && v > 0.0 && v < 1e30) return "";
    return "expected " + (known.empty() ? "" : known + " or ") + "a positive number, got '" + value + "'";
  }
  if (!spec.choices.empty()) return "expected one of " + known + ", got '" + value + "'";
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
  if (std::find(spec.choices.begin(), spec.choices.end(), value) != spec.choices.end()) {
    values_[name] = value;
  } else if (spec.positive_real) {
    std::ostringstream canonical;
    canonical << std::strtod(value.c_str(), nullptr);
    values_[name] = canonical.str();
  } else {
    values_[name] = std::to_string(std::stoll(value));
  }
}

const std::string& BackendParams::get(const std::string& name) const {
  const auto it = values_.find(name);
  return it != values_.end() ? it->second : spec_of(name).default_value;
}

int64_t BackendParams::integer(const std::string& name) const { return std::stoll(get(name)); }

double BackendParams::real(const std::string& name) const { return std::strtod(get(name).c_str(), nullptr); }

std::string BackendParams::misplaced_for(const std::string& backend) const {
  for (const auto& [name, value] : values_)
    if (!belongs_to(spec_of(name), backend)) return flag_of(spec_of(name)) + " is a parameter of " + families_of(spec_of(name));
  return "";
}

}  // namespace sdfbench
