#include "renderers/renderer.h"

#include <algorithm>
#include <cstdlib>

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
