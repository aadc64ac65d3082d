#pragma once
// The one interface every backend implements (docs/design.md, "Backends"): prepare a scene once,
// then render frames. What a backend must do and what it receives, nothing else: a backend is
// declared in renderers/backend.h and created by name through renderers/backend_registry.h.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "renderers/backend_params.h"
#include "renderers/structure_cache_options.h"
#include "renderers/work_counters.h"
#include "scenes/scene.h"

namespace sdfbench {

enum class RenderMode { Primary, Shadow, Whitted };
std::optional<RenderMode> parse_render_mode(const std::string& text);
std::string to_string(RenderMode mode);

struct BackendOptions {
  std::string device = "lavapipe";  // Vulkan device: "lavapipe", "gpu", an index or a name substring
  unsigned threads = 0;             // CPU worker threads (Embree); 0: as many as lavapipe uses
  bool validation = false;          // enable VK_LAYER_KHRONOS_validation and count its messages
  // whitted on Vulkan: one ray per pixel per dispatch (true) or each pixel's whole ray tree in one
  // invocation (false); unset: passes only on a device with a loop cap (loop_cap_probe.h).
  std::optional<bool> whitted_passes;
  CacheOptions cache;        // backends that store a structure: --cache FILE, --on-bad-cache
  // The backends' own parameters (backend_params.h): on the command side the values given; a
  // backend receives every parameter it owns, resolved (backend_registry.h, resolve_params).
  BackendParams params;
  // SDF Vulkan backends: #defines prepended to the kernel (the time-breakdown variants of
  // tests/bench/sdf_kernel_bench.cpp); empty for every real run.
  std::string kernel_defines;
};

struct FrameRequest {
  uint32_t width = 0;
  uint32_t height = 0;
  RenderMode mode = RenderMode::Primary;
  bool readback = true;  // false for timed frames whose pixels are not looked at
  std::optional<uint32_t> max_depth;  // whitted recursion limit (--max-depth); unset: render.max_depth
  bool counters = false;  // an instrumented frame: count every ray's work (never for timed frames)
};

// Image and AOVs of the primary rays, row-major, top row first.
struct FrameImages {
  uint32_t width = 0, height = 0;
  std::vector<glm::vec4> color;           // display-encoded RGBA in [0, 1]
  std::vector<float> depth;               // ray parameter t of the primary hit (0: miss)
  std::vector<uint32_t> instance_id;      // instance index, or NO_INSTANCE / FLOOR_INSTANCE
  std::vector<uint32_t> primitive_id;     // triangle index within the mesh
  std::vector<glm::vec3> normal;          // world shading normal facing the camera
  std::vector<uint32_t> steps;            // instrumented frames: sphere-tracing steps of all the pixel's rays (SDF backends)
};

struct FrameResult {
  double device_ms = -1.0;  // GPU timestamp difference x timestampPeriod; -1 when not available
  double wall_ms = 0.0;     // submit + wait (Vulkan) or the whole frame (CPU)
  uint64_t rays = 0;        // every ray traced (primary + shadow + secondary)
  WorkCounters counters;    // instrumented frames: the work of all rays (per ray: / rays)
  // Pixels cut short, by lavapipe's loop limit (docs/limits.md "The loop limit") or by the kernel's own
  // bound on a traversal (bound_pixels of them): when not 0, the image and the frame time are invalid.
  uint64_t truncated_pixels = 0;
  uint64_t bound_pixels = 0;
  FrameImages images;       // filled when FrameRequest::readback
};

// What a backend's structures cost (an SDF's mesh grids + scene hash, a BVH's trees): build time
// (as built, also when they came from the cache) and payload bytes.
struct StructureStats {
  double build_ms = 0;
  uint64_t bytes = 0;
  // A sampled field's voxel per instance, in world units (sdf-bricks; empty for exact structures):
  // its depth error is also reported in voxels.
  std::vector<float> instance_voxels;
  // What the backend chose for a parameter given as "auto" ("brick_fetch=sampler"); the CSV's
  // backend_resolved column.
  std::string resolved;
  // A BVH's quality (renderers/bvh/bvh_quality.h): SAH cost, end-point overlap, inner nodes.
  std::optional<double> sah, epo;
  std::optional<uint64_t> nodes;
};

class Renderer {
 public:
  virtual ~Renderer() = default;
  virtual std::string name() const = 0;
  virtual std::string device_name() const = 0;
  virtual std::string driver_name() const = 0;
  virtual void prepare(const Scene& scene) = 0;
  virtual FrameResult render(const FrameRequest& request) = 0;
  // Validation-layer warnings and errors seen so far (0 when validation is off or for CPU).
  virtual uint32_t validation_messages() const { return 0; }
  virtual std::optional<StructureStats> structure_stats() const { return std::nullopt; }
};

// "<backend>: lavapipe's loop limit ... cut N pixels short: ..." for a frame with truncated pixels
// (docs/limits.md "The loop limit"); empty when none were.
std::string truncation_error(const std::string& backend, const FrameResult& frame);

// Worker threads for CPU backends: options.threads, else LP_NUM_THREADS (what lavapipe
// uses), else the hardware concurrency.
unsigned cpu_thread_count(const BackendOptions& options);

}  // namespace sdfbench
