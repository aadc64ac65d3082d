#pragma once
// The backends, each described once next to its code (pbrt's central table of self-describing
// entries): its name, kind, what it supports, the parameters it owns, its factory and how reports
// pair it with others. The commands' flags and help, the sweep's axes, the CSV's parameter columns
// and their read-back, `sdfbench backends` and the report's pair tables are all made from this
// table; a new backend adds its declaration to builtin_backends() (backend_registry.cpp), or a
// program registers one at run time with register_backend() before it builds its commands
// (docs/adding-a-backend.md).
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "renderers/backend_params.h"
#include "renderers/renderer.h"

namespace sdfbench {

struct BackendPartner {
  std::string other;  // the backend this one is set against in the reports' pair tables
  std::string what;   // the comparison in words ("a sampled per-mesh field against a BVH in a compute kernel")
};

using BackendFactory = std::function<std::unique_ptr<Renderer>(const BackendOptions&)>;
// The factory of a renderer class constructed from BackendOptions.
template <class R>
BackendFactory factory() {
  return [](const BackendOptions& options) { return std::make_unique<R>(options); };
}

struct BackendInfo {
  std::string name;
  // The kind of method, for the reports' "which structure wins where": "cpu-bvh" (Embree),
  // "triangles" (no hierarchy), "compute-bvh", "driver-rt", "sdf-exact" (exact distances),
  // "sdf-sampled" (a sampled field), "sdf-cpu".
  std::string kind;
  std::string summary;            // one line, for help and `sdfbench backends`
  bool vulkan = true;             // runs on the Vulkan device (--device); else on the CPU
  std::vector<ParamSpec> params;  // the parameters it owns, with its own defaults and choices
  bool counters = false;          // instrumented frames count its traversal work
  bool steps = false;             // ... including sphere-tracing steps per pixel (render --heatmap)
  bool stores_structure = false;  // builds SDF structures: --cache, build time and bytes in its rows
  std::vector<BackendPartner> partners;
  bool in_table = true;           // `sdfbench table` runs it unless --backends says otherwise
  BackendFactory create;
};

// Every backend, built-in ones first, in the order help, tables and reports list them.
const std::vector<BackendInfo>& backends();
// Adds a backend (a test's toy, a plug-in); throws Error for a name already taken or a parameter
// whose name another backend declares with another kind.
void register_backend(BackendInfo info);
// Throws Error for an unknown name, listing the known ones.
const BackendInfo& backend_info(const std::string& name);
void check_backend_name(const std::string& name);
std::vector<std::string> backend_names();
std::string backend_list();  // "embree, tri-aabb, ..."
// The names of the backends that `table` runs by default, comma-separated.
std::string default_table_backends();

// Every backend's parameters, one entry per name (the first declaration; flags accept the union
// of the choices), in CSV column order.
const std::vector<ParamSpec>& param_catalogue();
const ParamSpec& catalogue_spec(const std::string& name);  // throws Error for an unknown parameter
bool owns(const BackendInfo& backend, const std::string& param);
std::string owners_of(const std::string& param);  // "sdf-hash, sdf-octree, sdf-cpu"

// Throws Error naming the flag when a given parameter is taken by none of `backends` (it would
// change nothing): "--octree-depth is a parameter of sdf-octree, sdf-bricks, sdf-cpu; no backend of
// this run (embree) takes it".
void check_params_taken(const BackendParams& given, const std::vector<std::string>& backends);
// What `backend` reads: each parameter it owns as given (checked against its own choices; throws
// Error naming the flag and the backend) or its default; parameters it does not own are left out.
BackendParams resolve_params(const BackendInfo& backend, const BackendParams& given);
// The resolved parameters that its CSV row records (those whose only_when condition holds).
std::map<std::string, std::string> recorded_params(const BackendInfo& backend, const BackendParams& resolved);

// Creates the backend with its own parameters resolved from options.params (resolve_params).
std::unique_ptr<Renderer> create_renderer(const std::string& name, const BackendOptions& options);

}  // namespace sdfbench
