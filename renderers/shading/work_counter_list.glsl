// The work counters of instrumented frames (docs/commands.md "Counters"), the one list the GLSL
// and the C++ share: X(ID, index) per counter, index its place in a pixel's counters, in
// WorkCounters and among the CSV's <name>_per_ray columns (0, 1, 2, ... in this order).
// shading_types.glsl and gpu_types.h make COUNTER_<ID> = index and COUNTER_KINDS of it. GLSL has
// no string literals, so each counter's name, report label and documentation are its entry in
// renderers/work_counters.cpp's table, which does not compile until it has one.
#ifndef SDFBENCH_WORK_COUNTER_LIST_GLSL
#define SDFBENCH_WORK_COUNTER_LIST_GLSL

#define WORK_COUNTERS(X)   \
  X(STEPS, 0u)             \
  X(INSTANCE_EVALS, 1u)    \
  X(TRIANGLE_EVALS, 2u)    \
  X(AABB_TESTS, 3u)        \
  X(TRIANGLE_TESTS, 4u)    \
  X(OUT_OF_STEPS, 5u)      \
  X(FIELD_SAMPLES, 6u)     \
  X(CELL_SETS, 7u)         \
  /* a new counter: the next index, on a line above this one */

// For WORK_COUNTERS(X): COUNTER_KINDS = 0u WORK_COUNTERS(WORK_COUNTER_PLUS_ONE).
#define WORK_COUNTER_PLUS_ONE(ID, index) +1u

#endif
