#include "renderers/work_counters.h"

namespace sdfbench {

namespace {

using enum CounterGroup;
// One entry per counter of work_counter_list.glsl, in its order.
constexpr std::array<CounterInfo, COUNTER_KINDS> kCounters = {{
    {COUNTER_STEPS, "steps", "steps/ray", evaluations,
     "sphere-tracing steps: scene-distance queries along a ray, inside the hash box"},
    {COUNTER_INSTANCE_EVALS, "instance_evals", "instance evals/ray", evaluations,
     "instance distance evaluations: a mesh grid queried in an instance's frame (sdf-bricks: an instance traced over a "
     "segment, or evaluated at a step with `--brick-trace min`; sdf-global: a listed instance tested exactly over a window)"},
    {COUNTER_TRIANGLE_EVALS, "triangle_evals", "triangle evals/ray", evaluations, "point-triangle distances computed"},
    {COUNTER_AABB_TESTS, "aabb_tests", "AABB tests/ray", tests,
     "tri-aabb: ray-box slab tests (every instance, per closest-hit ray); bvh: child boxes tested (2 per node visited, "
     "both levels); SDF: a listed instance's box tested against the best distance so far, which skips the instance when "
     "no nearer"},
    {COUNTER_TRIANGLE_TESTS, "triangle_tests", "triangle tests/ray", tests,
     "ray-triangle tests (Möller–Trumbore): tri-aabb's and bvh's traversal; the SDF backends' exact hit (`--hit exact`)"},
    {COUNTER_OUT_OF_STEPS, "out_of_steps", "out of steps/ray", rays,
     "rays whose march ended by `--max-steps` (per ray: the fraction of rays); with `--hit exact` the rest of such a "
     "ray's segment is tested against the instance it last converged on"},
    {COUNTER_FIELD_SAMPLES, "field_samples", "field samples/ray", evaluations,
     "trilinear samples of a brick field (8 texels or one filtered fetch; in an empty brick 8 coarse texels, "
     "sdf-global: one)"},
    {COUNTER_CELL_SETS, "cell_sets", "cell sets/ray", evaluations,
     "reference cells whose (instance, triangle) set was tested (`--exact-lists triangles`; 0 with the instance lists)"},
}};

// Entry k is counter k: a missing, extra or misplaced entry (or a gap in the list's ids) fails here.
constexpr bool table_matches_list() {
  for (uint32_t k = 0; k < COUNTER_KINDS; ++k)
    if (kCounters[k].id != k || !kCounters[k].name || !kCounters[k].label || !kCounters[k].doc) return false;
  return true;
}
static_assert(table_matches_list(), "kCounters must have one entry per WORK_COUNTERS line, in its order");

}  // namespace

const std::array<CounterInfo, COUNTER_KINDS>& counter_table() { return kCounters; }

const std::array<const char*, COUNTER_KINDS>& counter_names() {
  static const std::array<const char*, COUNTER_KINDS> names = [] {
    std::array<const char*, COUNTER_KINDS> n{};
    for (const CounterInfo& c : kCounters) n[c.id] = c.name;
    return n;
  }();
  return names;
}

WorkCounters sum_counters(const std::vector<uint32_t>& pixel_counts, uint32_t kinds) {
  WorkCounters totals;
  for (uint32_t k = 0; k < COUNTER_KINDS; ++k) {
    if (!(kinds & counter_bit(k))) continue;
    uint64_t sum = 0;
    for (size_t i = k; i < pixel_counts.size(); i += COUNTER_KINDS) sum += pixel_counts[i];
    totals[k] = sum;
  }
  return totals;
}

std::vector<uint32_t> pixel_steps(const std::vector<uint32_t>& pixel_counts, uint32_t kinds) {
  std::vector<uint32_t> steps;
  if (!(kinds & counter_bit(COUNTER_STEPS))) return steps;
  for (size_t i = COUNTER_STEPS; i < pixel_counts.size(); i += COUNTER_KINDS) steps.push_back(pixel_counts[i]);
  return steps;
}

}  // namespace sdfbench
