// Entry point shared by the Vulkan backends. The backend's .comp file (vk-rt: its ray-generation
// shader, which defines RAY_GENERATION) declares its own scene bindings (binding >= 8) and
// closest_hit/any_hit, then includes this file. An invocation renders one pixel of a tile.
// VulkanFrameRunner compiles it per mode and scene: SHADING_MODE (MODE_*), SHADING_TEXTURES and
// SHADING_IMPLICITS (bool), COUNTERS (0 or 1, work_counters.glsl), WHITTED_PASSES (0 or 1).
//
// whitted traces a pixel's whole ray tree in one invocation, its ray stack in registers /
// private memory. On drivers with a per-invocation loop cap (lavapipe before Mesa 25:
// loop_cap_probe.h) WHITTED_PASSES 1 traces one ray of each pixel per dispatch instead, the
// stack and the pixel's state kept in buffers between passes.
#ifdef RAY_GENERATION
#define LAUNCH_ID gl_LaunchIDEXT.xy
#define LAUNCH_WIDTH gl_LaunchSizeEXT.x
#else
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
// lavapipe runs a work group 8 invocations (one SIMD vector) at a time, in invocation order: each
// eight trace a 4x2 block of pixels rather than a row of 8, whose rays stay closer together
// (sdf-octree on thesis:bunny:1000: 1.13x, tests/bench/README.md).
uvec2 local_pixel() {
  uint i = gl_LocalInvocationIndex, vector = i >> 3u, lane = i & 7u;
  return uvec2((vector & 1u) * 4u + (lane & 3u), (vector >> 1u) * 2u + (lane >> 2u));
}
#define LAUNCH_ID (gl_WorkGroupID.xy * 8u + local_pixel())
#define LAUNCH_WIDTH (gl_NumWorkGroups.x * gl_WorkGroupSize.x)
#endif

layout(push_constant) uniform TilePush {
  uvec4 tile;  // xy: pixel offset of this dispatch's tile; z: whitted pass (0: the first); w: 2 (loop_limit_hit)
} push;

// WHITTED_PASSES, per invocation of a tile: its ray stack and its state between passes;
// `pending` is raised while any pixel of the tile has rays left.
layout(std430, binding = 6) buffer StackBlock { PathEntry stacks[]; };
layout(std430, binding = 7) buffer StateBlock {
  uint pending;
  PixelState states[];
};

#if WHITTED_PASSES
uint stack_base;

PathEntry stack_load(uint i) {
  return stacks[stack_base + i];
}

void stack_store(uint i, PathEntry e) {
  stacks[stack_base + i] = e;
}
#else
PathEntry stack[STACK_SIZE];

PathEntry stack_load(uint i) {
  return stack[i];
}

void stack_store(uint i, PathEntry e) {
  stack[i] = e;
}
#endif

uint shading_mode() {
  return SHADING_MODE;
}

bool has_textures() {
  return SHADING_TEXTURES;
}

bool has_implicits() {
  return SHADING_IMPLICITS;
}

#include "shading.glsl"

// A backend whose traversal can run out of a fixed resource or reach its hard iteration bound
// (bvh: its stacks, one visit per node; sdf: the octree's depth) defines TRAVERSAL_OVERFLOW as
// that flag: the pixel is then counted as cut short, never silently wrong.
#ifndef TRAVERSAL_OVERFLOW
#define TRAVERSAL_OVERFLOW false
#endif

// lavapipe (Mesa 22.3) gives an invocation 65535 loop iterations in all, then silently ends every
// loop at its first check. A loop of push.tile.w = 2 iterations, a run-time count the compiler
// cannot unroll, that stops short says this invocation ran out: its pixel is cut short.
bool loop_limit_hit() {
  uint done = 0u;
  for (uint i = 0u; i < push.tile.w; ++i) done++;
  return done != push.tile.w;
}

#if COUNTERS
// Adds this invocation's work to the pixel's counters (whitted: one pass of several).
void store_counters(uint index, bool first) {
  for (uint k = 0u; k < COUNTER_KINDS; ++k) {
    uint i = index * COUNTER_KINDS + k;
    pixel_counters[i] = first ? counted[k] : pixel_counters[i] + counted[k];
  }
}
#endif

void main() {
  uvec2 pixel = LAUNCH_ID + push.tile.xy;
  if (pixel.x >= frame.image.x || pixel.y >= frame.image.y) return;
  uint index = pixel.y * frame.image.x + pixel.x;
  uint slot = LAUNCH_ID.y * LAUNCH_WIDTH + LAUNCH_ID.x;
#if WHITTED_PASSES
  stack_base = slot * STACK_SIZE;
  bool first = SHADING_MODE != MODE_WHITTED || push.tile.z == 0u;
#else
  const bool first = true;
#endif
  PixelState s;
  PixelAov aov;
  PathEntry ray;
  if (first) {
    begin_pixel(s, aov);
    ray = primary_ray(pixel);
  } else {
    // WHITTED_PASSES: the next ray of the stack.
    s = states[slot];
    if (s.counters.x == 0u) return;
    ray = pop_ray(s);
  }
  // One call site of trace_ray: the driver inlines every call, and lavapipe's compile time grows
  // faster than the code (two sites made a whitted kernel with implicit objects take 3.6x as long).
  for (;;) {
    trace_ray(ray, s, aov);
    if (SHADING_MODE != MODE_WHITTED || WHITTED_PASSES == 1 || s.counters.x == 0u) break;
    ray = pop_ray(s);
  }
  // ids.w: why the pixel was cut short, CUT_LOOP_CAP | CUT_TRAVERSAL_BOUND (0: not).
  uint cut = (loop_limit_hit() ? CUT_LOOP_CAP : 0u) | (TRAVERSAL_OVERFLOW ? CUT_TRAVERSAL_BOUND : 0u);
  if (first) {
    out_aov[index].normal_depth = vec4(aov.normal, aov.depth);
    out_aov[index].ids = uvec4(aov.instance, aov.prim, 0u, cut);
  } else if (cut != 0u) {
    out_aov[index].ids.w |= cut;
  }
#if COUNTERS
  store_counters(index, first);
#endif
  if (SHADING_MODE == MODE_WHITTED && WHITTED_PASSES == 1) {
    states[slot] = s;
    if (s.counters.x > 0u) {
      pending = 1u;
      return;
    }
  }
  out_color[index] = pixel_color(s);
  out_aov[index].ids.z = s.counters.y;
}
