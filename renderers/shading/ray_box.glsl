// The part [t0, t1] of the ray o + t d inside the box [lo, hi], narrowed in place (slabs, Kay &
// Kajiya 1986); axes the ray runs parallel to are skipped. Empty when t0 > t1 afterwards.
// Shared by the SDF backends' exact hit in GLSL and (gpu_types.h) C++.
#ifndef SDFBENCH_RAY_BOX_GLSL
#define SDFBENCH_RAY_BOX_GLSL

SHARED_FN void clip_to_box(vec3 o, vec3 d, vec3 lo, vec3 hi, INOUT(float) t0, INOUT(float) t1) {
  for (int axis = 0; axis < 3; ++axis) {
    if (d[axis] == 0.0f) continue;
    float a = (lo[axis] - o[axis]) / d[axis];
    float b = (hi[axis] - o[axis]) / d[axis];
    t0 = max(t0, min(a, b));
    t1 = min(t1, max(a, b));
  }
}

#endif
