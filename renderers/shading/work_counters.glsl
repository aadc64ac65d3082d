// Work counters of instrumented frames (docs/commands.md "Counters"). VulkanFrameRunner compiles those
// kernels with COUNTERS 1: the backend's trace code adds its work to `counted` with COUNT, and
// render_main.glsl adds `counted` to the pixel's entry of the counter buffer. Otherwise COUNT is
// empty, so timed frames pay nothing.
#if COUNTERS
layout(std430, binding = COUNTERS_BINDING) buffer CounterBlock { uint pixel_counters[]; };  // COUNTER_KINDS per pixel
#define WORK_COUNTER_ZERO(ID, index) 0u,
uint counted[COUNTER_KINDS] = {WORK_COUNTERS(WORK_COUNTER_ZERO)};  // an initialiser, not a loop (docs/limits.md "The loop limit")
#undef WORK_COUNTER_ZERO
#define COUNT(kind, n) counted[kind] += (n)
#else
#define COUNT(kind, n)
#endif
