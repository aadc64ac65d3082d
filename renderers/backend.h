#pragma once
// What a backend declares about itself, next to its code: its name, kind, capabilities, the
// parameters it owns and its factory. A backend includes this header (and renderer.h, which it
// implements); the registry (backend_registry.h) includes the declarations, never the reverse.
// The commands' flags and help, the sweep's axes, the CSV's parameter columns and their
// read-back, `sdfbench backends` and the report's pair tables are all made from these entries
// (docs/adding-a-backend.md).
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "renderers/backend_params.h"
#include "renderers/renderer.h"

namespace sdfbench {

// The kind of method, for the reports' "which structure wins where".
enum class BackendKind {
  CpuBvh,      // a BVH on the CPU (Embree)
  Triangles,   // no hierarchy: every triangle of every box the ray enters
  ComputeBvh,  // a BVH traversed in a compute kernel
  DriverRt,    // the driver's own ray tracing
  SdfExact,    // sphere tracing exact per-mesh distances
  SdfSampled,  // sphere tracing a sampled field
  SdfCpu,      // the SDF reference tracer on the CPU
};
std::string to_string(BackendKind kind);  // "cpu-bvh", "triangles", "compute-bvh", "driver-rt", "sdf-exact", ...
// Sphere tracers (exact, sampled or the CPU reference).
inline bool is_sdf(BackendKind kind) {
  return kind == BackendKind::SdfExact || kind == BackendKind::SdfSampled || kind == BackendKind::SdfCpu;
}

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
  BackendKind kind = BackendKind::Triangles;
  std::string summary;            // one line, for help and `sdfbench backends`
  std::vector<ParamSpec> params;  // the parameters it owns, with its own defaults and choices
  // Capabilities: what the commands may ask of it.
  bool vulkan = true;             // runs on the Vulkan device (--device); else on the CPU
  bool counters = false;          // instrumented frames count its traversal work
  bool steps = false;             // ... including sphere-tracing steps per pixel (render --heatmap)
  bool stores_structure = false;  // builds stored structures: --cache, build time and bytes in its rows
  bool scene_hash = false;        // its structure has the thesis' scene hash and octrees (build, render --view)
  std::vector<BackendPartner> partners;
  bool in_table = true;           // `sdfbench table` runs it unless --backends says otherwise
  BackendFactory create;
};

}  // namespace sdfbench
