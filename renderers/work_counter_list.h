#pragma once
// The work counters of instrumented frames (docs/commands.md "Counters"): ONE line per counter,
//   X(ID, name, "report label", group, "backends", "what is counted")
// and everything follows from it: COUNTER_<ID> = the line's place (0, 1, 2, ...: its index in a
// pixel's counters, in WorkCounters and among the CSV's <name>_per_ray columns), COUNTER_KINDS
// (renderers/shading/gpu_types.h); counter_table() and counter_names() (renderers/work_counters.cpp);
// the kernels' COUNTER_<ID>, COUNTER_KINDS and `counted` (renderers/vulkan/shader_compiler.cpp
// prepends them to every kernel as #defines, work_counter_glsl_prelude()); the CSV's and JSON's
// columns and the markdown reports' (harness/measurement.cpp, harness/markdown_report.cpp); and the
// docs' Counters table (`harness/scripts/update_docs.sh`, checked by WorkCounters.DocsListEvery...).
// group (CounterGroup, renderers/work_counters.h): evaluations, tests or rays, where a report puts
// its column. backends: the docs' "backends" cell (the masks that decide it stay with the backends,
// kSdfCounters... in renderers/work_counters.h). A new counter: a line here (at the end: the CSV's
// column order), its kernel's COUNT(COUNTER_<ID>, n) and its backends' mask.
// clang-format off
#define WORK_COUNTER_TABLE(X) \
  X(STEPS, steps, "steps/ray", evaluations, "sdf-*", "sphere-tracing steps: scene-distance queries along a ray, inside the hash box") \
  X(INSTANCE_EVALS, instance_evals, "instance evals/ray", evaluations, "sdf-*", "instance distance evaluations: a mesh grid queried in an instance's frame (sdf-bricks: an instance traced over a segment, or evaluated at a step with `--brick-trace min`; sdf-global: a listed instance tested exactly over a window)") \
  X(TRIANGLE_EVALS, triangle_evals, "triangle evals/ray", evaluations, "sdf-hash, sdf-octree, sdf-cpu", "point-triangle distances computed") \
  X(AABB_TESTS, aabb_tests, "AABB tests/ray", tests, "tri-aabb, bvh, sdf-*", "tri-aabb: ray-box slab tests (every instance, per closest-hit ray); bvh: child boxes tested (the node width per node visited, both levels); SDF: a listed instance's box tested against the best distance so far, which skips the instance when no nearer") \
  X(TRIANGLE_TESTS, triangle_tests, "triangle tests/ray", tests, "tri-aabb, bvh, sdf-*", "ray-triangle tests (Möller–Trumbore): tri-aabb's and bvh's traversal; the SDF backends' exact hit (`--hit exact`)") \
  X(OUT_OF_STEPS, out_of_steps, "out of steps/ray", rays, "sdf-*", "rays whose march ended by `--max-steps` (per ray: the fraction of rays); with `--hit exact` the rest of such a ray's segment is tested against the instance it last converged on") \
  X(FIELD_SAMPLES, field_samples, "field samples/ray", evaluations, "sdf-bricks, sdf-global", "trilinear samples of a brick field (8 texels or one filtered fetch; in an empty brick 8 coarse texels, sdf-global: one)") \
  X(CELL_SETS, cell_sets, "cell sets/ray", evaluations, "sdf-global", "reference cells whose (instance, triangle) set was tested (`--exact-lists triangles`; 0 with the instance lists)") \
  X(NODE_VISITS, node_visits, "nodes/ray", tests, "bvh", "BVH nodes visited, both levels (each tests all its child boxes: aabb_tests = the node width x node_visits)") \
  /* a new counter: a line above this one */
// clang-format on
