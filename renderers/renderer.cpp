#include "renderers/renderer.h"

#include <algorithm>
#include <cstdlib>

#include "renderers/bvh/bvh_renderer.h"
#include "renderers/embree/embree_renderer.h"
#include "renderers/sdf/sdf_cpu_renderer.h"
#include "renderers/sdf_vk/sdf_bricks_renderer.h"
#include "renderers/sdf_vk/sdf_global_renderer.h"
#include "renderers/sdf_vk/sdf_vk_renderer.h"
#include "renderers/tri_aabb/tri_aabb_renderer.h"
#include "renderers/vk_rt/vk_rt_renderer.h"
#include "util/cpu_info.h"
#include "util/error.h"

namespace sdfbench {

std::optional<RenderMode> parse_render_mode(const std::string& text) {
  if (text == "primary") return RenderMode::Primary;
  if (text == "shadow") return RenderMode::Shadow;
  if (text == "whitted") return RenderMode::Whitted;
  return std::nullopt;
}

std::string to_string(RenderMode mode) {
  switch (mode) {
    case RenderMode::Primary: return "primary";
    case RenderMode::Shadow: return "shadow";
    case RenderMode::Whitted: return "whitted";
  }
  return "?";
}

const std::vector<std::string>& backend_names() {
  static const std::vector<std::string> names = {"embree", "tri-aabb", "bvh", "vk-rt", "sdf-hash", "sdf-octree", "sdf-bricks", "sdf-global", "sdf-cpu"};
  return names;
}

bool is_sdf_backend(const std::string& name) { return name.rfind("sdf-", 0) == 0; }

std::unique_ptr<Renderer> create_renderer(const std::string& name, const BackendOptions& options) {
  if (name == "embree") return std::make_unique<EmbreeRenderer>(options);
  if (name == "tri-aabb") return std::make_unique<TriAabbRenderer>(options);
  if (name == "vk-rt") return std::make_unique<VkRtRenderer>(options);
  if (name == "bvh") return std::make_unique<BvhRenderer>(options);
  if (name == "sdf-hash" || name == "sdf-octree") return std::make_unique<SdfVkRenderer>(name, options);
  if (name == "sdf-bricks") return std::make_unique<SdfBricksRenderer>(options);
  if (name == "sdf-global") return std::make_unique<SdfGlobalRenderer>(options);
  if (name == "sdf-cpu") return std::make_unique<SdfCpuRenderer>(options);
  check_backend_name(name);
  throw Error("internal: backend '" + name + "' has no constructor");
}

void check_backend_name(const std::string& name) {
  const std::vector<std::string>& names = backend_names();
  if (std::find(names.begin(), names.end(), name) != names.end()) return;
  std::string known;
  for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
  throw Error("unknown backend '" + name + "' (available: " + known + ")");
}

sdf::SceneHashParams scene_hash_params_for(const std::string& backend, const BackendOptions& options) {
  sdf::SceneHashParams params = options.scene_hash;
  if (backend == "sdf-hash") {
    params.octree_depth = 0;
    if (!options.hash_cell_given) params.hash_cell = 1.0f;
  }
  return params;
}

std::string truncation_error(const std::string& backend, const FrameResult& frame) {
  if (frame.truncated_pixels == 0) return "";
  if (frame.bound_pixels > 0)
    return backend + ": " + std::to_string(frame.bound_pixels) +
           " pixels reached the traversal's hard bound (its stack, or one visit per node or level; a degenerate "
           "structure or non-finite coordinates): the image and timing are invalid";
  return backend + ": lavapipe's loop limit (65535 iterations per invocation) cut " +
         std::to_string(frame.truncated_pixels) + " pixels short: the image and timing are invalid";
}

unsigned cpu_thread_count(const BackendOptions& options) {
  if (options.threads > 0) return options.threads;
  if (const char* env = std::getenv("LP_NUM_THREADS"); env && std::atoi(env) > 0) return std::atoi(env);
  return hardware_threads();
}

}  // namespace sdfbench
