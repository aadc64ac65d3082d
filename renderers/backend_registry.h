#pragma once
// The registry of backends: every declaration (backend.h) by name, and what the commands ask of
// them. The built-in ones are one table (builtin_backends.cpp); a program registers its own at run
// time with register_backend() before it builds its commands (docs/adding-a-backend.md).
#include <map>
#include <string>
#include <vector>

#include "renderers/backend.h"
#include "renderers/backend_params.h"

namespace sdfbench {

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
// The backends with a capability, comma-separated ("sdf-hash, sdf-octree, sdf-bricks, sdf-cpu").
std::string backends_with(bool BackendInfo::*capability);
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

// The reference's options: the run's, with the reference backend's own parameters at their
// defaults (the frame every image is checked against is always the reference configuration,
// embree's single rays over instances, whatever the run asks of that backend).
BackendOptions reference_options(const std::string& reference, const BackendOptions& options);
// Is `backend` with these options the reference itself (the reference backend, its own
// parameters given at their defaults, if at all)? Another configuration of it is checked like
// any backend.
bool is_reference_configuration(const std::string& backend, const std::string& reference, const BackendOptions& options);

// Creates the backend with its own parameters resolved from options.params (resolve_params).
std::unique_ptr<Renderer> create_renderer(const std::string& name, const BackendOptions& options);

}  // namespace sdfbench
