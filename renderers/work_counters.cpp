#include "renderers/work_counters.h"

namespace sdfbench {

namespace {

// One entry per line of WORK_COUNTER_TABLE, in its order.
#define WORK_COUNTER_INFO(ID, name, label, group, backends, doc) {COUNTER_##ID, #name, label, CounterGroup::group, backends, doc},
constexpr std::array<CounterInfo, COUNTER_KINDS> kCounters = {{WORK_COUNTER_TABLE(WORK_COUNTER_INFO)}};
#undef WORK_COUNTER_INFO

// Entry k is counter k, with every word.
constexpr bool table_matches_list() {
  for (uint32_t k = 0; k < COUNTER_KINDS; ++k)
    if (kCounters[k].id != k || !*kCounters[k].name || !*kCounters[k].label || !*kCounters[k].backends ||
        !*kCounters[k].doc)
      return false;
  return true;
}
static_assert(table_matches_list(), "every WORK_COUNTER_TABLE line needs a name, label, backends and doc");

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

std::string counters_markdown() {
  std::string text = "| counter | what is counted | backends |\n|---|---|---|\n";
  for (const CounterInfo& c : kCounters)
    text += std::string("| ") + c.name + " | " + c.doc + " | " + c.backends + " |\n";
  return text;
}

const std::string& work_counter_glsl_prelude() {
  static const std::string prelude = [] {
    std::string text = "#define WORK_COUNTERS(X)";
#define WORK_COUNTER_GLSL(ID, ...) text += " X(" #ID ", " + std::to_string(COUNTER_##ID) + "u)";
    WORK_COUNTER_TABLE(WORK_COUNTER_GLSL)
#undef WORK_COUNTER_GLSL
    return text + "\n";
  }();
  return prelude;
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
