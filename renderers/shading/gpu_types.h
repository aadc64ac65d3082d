#pragma once
// shading_types.glsl seen from C++: buffer layouts, Ray, Hit and the shared constants; and the
// implicit primitives' distance and uv functions (implicit_sdf.glsl), and the ray-box and
// ray-triangle tests (ray_box.glsl, ray_triangle.glsl).
#include <array>
#include <cstdint>

#include <glm/glm.hpp>

#include "renderers/work_counter_list.h"

namespace sdfbench {
// The work counters' COUNTER_<ID> (a line's place in WORK_COUNTER_TABLE) and COUNTER_KINDS, as the
// kernels get them (work_counter_glsl_prelude(), renderers/work_counters.h).
namespace counter_ids {
#define WORK_COUNTER_ENUMERATOR(ID, ...) ID,
enum : uint32_t { WORK_COUNTER_TABLE(WORK_COUNTER_ENUMERATOR) kinds };
#undef WORK_COUNTER_ENUMERATOR
}  // namespace counter_ids
#define DECLARE_WORK_COUNTER(ID, ...) inline constexpr uint32_t COUNTER_##ID = counter_ids::ID;
WORK_COUNTER_TABLE(DECLARE_WORK_COUNTER)
#undef DECLARE_WORK_COUNTER
inline constexpr uint32_t COUNTER_KINDS = counter_ids::kinds;
}  // namespace sdfbench

namespace sdfbench::shading {
using namespace glm;
#include "shading_types.glsl"
#include "implicit_sdf.glsl"
#include "ray_box.glsl"
#include "ray_triangle.glsl"
}  // namespace sdfbench::shading

namespace sdfbench::shading {
// The GLSL #defines as typed C++ constants.
inline constexpr uint32_t NO_INSTANCE_VALUE = NO_INSTANCE;
inline constexpr uint32_t FLOOR_INSTANCE_VALUE = FLOOR_INSTANCE;
inline constexpr uint32_t CUT_TRAVERSAL_BOUND_BIT = CUT_TRAVERSAL_BOUND;
inline constexpr uint32_t NO_UV_TABLE_VALUE = NO_UV_TABLE;

// One pixel's work in an instrumented frame, indexed by COUNTER_* (the CPU tracers add to it).
using PixelCounts = std::array<uint32_t, COUNTER_KINDS>;
}  // namespace sdfbench::shading
