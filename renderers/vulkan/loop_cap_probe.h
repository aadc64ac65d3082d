#pragma once
// Whether a device silently caps the loop iterations of a shader invocation: lavapipe before
// Mesa 25 gives an invocation 65535 iterations in all, then ends every loop at its first check
// (docs/limits.md, "The loop limit"). Found by running a loop past that count once, not from the version.
#include "renderers/vulkan/vulkan_context.h"

namespace sdfbench {

constexpr uint32_t kLoopCapProbeTrips = 200000;

// True when the probe loop of kLoopCapProbeTrips iterations stopped short on this device.
bool has_loop_cap(const VulkanContext& context);

}  // namespace sdfbench
