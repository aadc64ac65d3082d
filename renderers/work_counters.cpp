#include "renderers/work_counters.h"

namespace sdfbench {

const std::array<const char*, COUNTER_KINDS>& counter_names() {
  static const std::array<const char*, COUNTER_KINDS> names = {"steps", "instance_evals", "triangle_evals", "aabb_tests",
                                                               "triangle_tests", "out_of_steps", "field_samples", "cell_sets"};
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
