#pragma once
// Work counters of instrumented frames (FrameRequest::counters; docs/commands.md "Counters"): which
// counters a backend has, and the frame totals from the per-pixel counts.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "renderers/shading/gpu_types.h"

namespace sdfbench {

// Frame totals indexed by COUNTER_*; a counter the backend does not have (tri-aabb takes no
// sphere-tracing steps) or cannot see (Embree exposes no traversal counts) stays empty.
using WorkCounters = std::array<std::optional<uint64_t>, COUNTER_KINDS>;

// Where a counter's column stands in a report (the markdown sweep tables): with what a ray's march
// evaluates, after them with the intersection tests, or not at all (a share of the rays, not work).
enum class CounterGroup { evaluations, tests, rays };

// One counter: its line of WORK_COUNTER_TABLE (renderers/work_counter_list.h).
struct CounterInfo {
  uint32_t id;           // COUNTER_<ID>
  const char* name;      // "cell_sets": the CSV's cell_sets_per_ray column, what `render --counters` prints
  const char* label;     // "cell sets/ray": a report's column title
  CounterGroup group;
  const char* backends;  // "sdf-global": the docs' "backends" cell
  const char* doc;       // what is counted: docs/commands.md "Counters" says it (counters_markdown())
};

// Every counter, in id order.
const std::array<CounterInfo, COUNTER_KINDS>& counter_table();
// Their names, by id.
const std::array<const char*, COUNTER_KINDS>& counter_names();

// docs/commands.md's "Counters" table, a row per counter (counter, what is counted, backends), each
// line ending in '\n': `sdfbench backends --counters-markdown table` prints it and
// harness/scripts/update_docs.sh puts it between the doc's markers.
std::string counters_markdown();

// What renderers/vulkan/shader_compiler.cpp prepends to every kernel: the counters as #defines,
// WORK_COUNTERS(X) with X(ID, index) per counter, "#define WORK_COUNTERS(X) X(STEPS, 0u) ...\n"
// (shading_types.glsl declares COUNTER_<ID> and COUNTER_KINDS of it, work_counters.glsl zeroes
// `counted`).
const std::string& work_counter_glsl_prelude();

// Which counters a backend has: bit k for COUNTER kind k.
inline constexpr uint32_t counter_bit(uint32_t kind) { return 1u << kind; }
// The exact SDF backends (a backend with other counters declares its own set in its folder):
// triangle_tests are the exact hit's ray-triangle tests (--hit exact).
inline constexpr uint32_t kSdfCounters = counter_bit(COUNTER_STEPS) | counter_bit(COUNTER_INSTANCE_EVALS) |
                                         counter_bit(COUNTER_TRIANGLE_EVALS) | counter_bit(COUNTER_AABB_TESTS) |
                                         counter_bit(COUNTER_TRIANGLE_TESTS) | counter_bit(COUNTER_OUT_OF_STEPS);
inline constexpr uint32_t kTriAabbCounters = counter_bit(COUNTER_AABB_TESTS) | counter_bit(COUNTER_TRIANGLE_TESTS);
// node child boxes tested, triangles tested, nodes visited
inline constexpr uint32_t kBvhCounters = kTriAabbCounters | counter_bit(COUNTER_NODE_VISITS);

// Sums `pixel_counts` (COUNTER_KINDS per pixel) over the frame for the counters in `kinds`.
WorkCounters sum_counters(const std::vector<uint32_t>& pixel_counts, uint32_t kinds);

// The steps of each pixel (the heat map), when the backend counts steps; else empty.
std::vector<uint32_t> pixel_steps(const std::vector<uint32_t>& pixel_counts, uint32_t kinds);

}  // namespace sdfbench
