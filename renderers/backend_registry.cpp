#include "renderers/backend_registry.h"

#include <algorithm>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "util/error.h"

namespace sdfbench {

std::vector<BackendInfo> builtin_backends();  // builtin_backends.cpp

namespace {

struct Registry {
  std::vector<BackendInfo> backends;
  std::vector<ParamSpec> catalogue;

  void add(BackendInfo info) {
    for (const BackendInfo& b : backends)
      if (b.name == info.name) throw Error("a backend named '" + info.name + "' is already registered");
    if (!info.create) throw Error("backend '" + info.name + "' has no factory");
    for (const ParamSpec& spec : info.params) {
      auto same = std::find_if(catalogue.begin(), catalogue.end(), [&](const ParamSpec& s) { return s.name == spec.name; });
      if (same == catalogue.end()) {
        catalogue.push_back(spec);
        continue;
      }
      if (same->kind != spec.kind)
        throw Error("backend '" + info.name + "': parameter '" + spec.name + "' is declared with another kind by " +
                    owners_of_in(spec.name));
      for (const std::string& c : spec.choices)  // the flag takes every backend's choices; each backend checks its own
        if (std::find(same->choices.begin(), same->choices.end(), c) == same->choices.end()) same->choices.push_back(c);
    }
    backends.push_back(std::move(info));
  }

  std::string owners_of_in(const std::string& param) const {
    std::string text;
    for (const BackendInfo& b : backends)
      if (owns(b, param)) text += (text.empty() ? "" : ", ") + b.name;
    return text;
  }
};

Registry& registry() {
  static Registry r = [] {
    Registry built;
    for (BackendInfo& info : builtin_backends())
      built.add(std::move(info));
    return built;
  }();
  return r;
}

std::string join(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& n : names) text += (text.empty() ? "" : ", ") + n;
  return text;
}

}  // namespace

const std::vector<BackendInfo>& backends() { return registry().backends; }

void register_backend(BackendInfo info) { registry().add(std::move(info)); }

const BackendInfo& backend_info(const std::string& name) {
  for (const BackendInfo& b : backends())
    if (b.name == name) return b;
  throw Error("unknown backend '" + name + "' (available: " + backend_list() + ")");
}

void check_backend_name(const std::string& name) { backend_info(name); }

std::vector<std::string> backend_names() {
  std::vector<std::string> names;
  for (const BackendInfo& b : backends()) names.push_back(b.name);
  return names;
}

std::string backend_list() { return join(backend_names()); }

std::string default_table_backends() {
  std::string text;
  for (const BackendInfo& b : backends())
    if (b.in_table) text += (text.empty() ? "" : ",") + b.name;
  return text;
}

const std::vector<ParamSpec>& param_catalogue() { return registry().catalogue; }

const ParamSpec& catalogue_spec(const std::string& name) {
  for (const ParamSpec& spec : param_catalogue())
    if (spec.name == name) return spec;
  throw Error("unknown backend parameter '" + name + "'");
}

bool owns(const BackendInfo& backend, const std::string& param) {
  return std::any_of(backend.params.begin(), backend.params.end(), [&](const ParamSpec& s) { return s.name == param; });
}

std::string owners_of(const std::string& param) { return registry().owners_of_in(param); }

std::string backends_with(bool BackendInfo::*capability) {
  std::vector<std::string> names;
  for (const BackendInfo& b : backends())
    if (b.*capability) names.push_back(b.name);
  return join(names);
}

std::string to_string(BackendKind kind) {
  switch (kind) {
    case BackendKind::CpuBvh: return "cpu-bvh";
    case BackendKind::Triangles: return "triangles";
    case BackendKind::ComputeBvh: return "compute-bvh";
    case BackendKind::DriverRt: return "driver-rt";
    case BackendKind::SdfExact: return "sdf-exact";
    case BackendKind::SdfSampled: return "sdf-sampled";
    case BackendKind::SdfCpu: return "sdf-cpu";
  }
  return "?";
}


void check_params_taken(const BackendParams& given, const std::vector<std::string>& run_backends) {
  for (const auto& [name, value] : given.values()) {
    const bool taken = std::any_of(run_backends.begin(), run_backends.end(),
                                   [&](const std::string& b) { return owns(backend_info(b), name); });
    if (!taken)
      throw Error(flag_of(catalogue_spec(name)) + " is a parameter of " + owners_of(name) + "; no backend of this run (" +
                  join(run_backends) + ") takes it");
  }
}

BackendParams resolve_params(const BackendInfo& backend, const BackendParams& given) {
  BackendParams resolved;
  for (const ParamSpec& spec : backend.params) {
    std::string why;
    if (!given.has(spec.name)) {
      // The default, typed as a given value is; one its declaration refuses, or spells otherwise
      // than the CSV would record it, is the declaration's error.
      const std::optional<TypedParam> value = parse_param(spec, spec.default_value, why);
      if (!value || value->text != spec.default_value)
        throw InternalError(backend.name + " declares " + spec.name + " with the default '" + spec.default_value +
                        "', " + (value ? "which it records as '" + value->text + "'" : why));
      resolved.set(spec.name, *value);
      continue;
    }
    // A flag's value was parsed against the catalogue's declaration (every backend's choices):
    // checked against this backend's own, not parsed again. One given as text (a test's, a CSV
    // row's) is parsed here, once.
    std::optional<TypedParam> value = given.typed(spec.name);
    if (value ? !param_accepts(spec, *value) : !(value = parse_param(spec, given.text(spec.name), why)))
      throw Error(flag_of(spec) + " " + given.text(spec.name) + ": " + backend.name + " takes " + describe_values(spec));
    resolved.set(spec.name, *value);
  }
  return resolved;
}

std::map<std::string, std::string> recorded_params(const BackendInfo& backend, const BackendParams& resolved) {
  std::map<std::string, std::string> out;
  for (const ParamSpec& spec : backend.params)
    if (spec.only_when_param.empty() || !resolved.has(spec.only_when_param) ||
        resolved.text(spec.only_when_param) == spec.only_when_value)
      out[spec.name] = resolved.text(spec.name);
  return out;
}

std::unique_ptr<Renderer> create_renderer(const std::string& name, const BackendOptions& options) {
  const BackendInfo& info = backend_info(name);
  BackendOptions own = options;
  own.params = resolve_params(info, options.params);
  return info.create(own);
}

BackendOptions reference_options(const std::string& reference, const BackendOptions& options) {
  BackendOptions out = options;
  for (const ParamSpec& spec : backend_info(reference).params) out.params.erase(spec.name);
  return out;
}

bool is_reference_configuration(const std::string& backend, const std::string& reference, const BackendOptions& options) {
  if (backend != reference) return false;
  const BackendParams resolved = resolve_params(backend_info(backend), options.params);
  const BackendParams defaults = resolve_params(backend_info(backend), BackendParams{});
  return resolved == defaults;
}

}  // namespace sdfbench
