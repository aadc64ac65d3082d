// Types shared by the GLSL kernels and the C++ (GLM) backends. Buffer structs hold only
// vec4/uvec4/mat4 members so that std140/std430 and C++ layouts are identical.
#ifndef SDFBENCH_SHADING_TYPES_GLSL
#define SDFBENCH_SHADING_TYPES_GLSL

#ifdef __cplusplus
#define OUT(T) T&
#define INOUT(T) T&
#define SHARED_FN inline
#else
#define OUT(T) out T
#define INOUT(T) inout T
#define SHARED_FN
#endif

#define MODE_PRIMARY 0u
#define MODE_SHADOW 1u
#define MODE_WHITTED 2u

#define MAX_DEPTH_LIMIT 16u  // whitted: deepest secondary ray (render.max_depth, --max-depth)
// A ray leaving a surface starts this x the largest magnitude that computed its hit point off the
// surface (~84 float ulps: p = origin + t dir and the ray-triangle t each round by a few).
#define RAY_OFFSET_RELATIVE 1e-5f
// ... plus, for an implicit object's hit (within its epsilon of the surface, not on it), this many
// of its hit epsilons (frame.tracing.w): the ray must start well outside the surface it leaves.
#define IMPLICIT_OFFSET_EPSILONS 20.0f
#define ENERGY_CUTOFF 1e-3f  // whitted: rays whose weight's largest component is below this are dropped
// Popping a ray of depth d pushes at most two of depth d + 1 (only when d < max_depth), so the
// stack never holds more than one pending ray per depth plus the pair just pushed.
#define STACK_SIZE (MAX_DEPTH_LIMIT + 1u)

// Work counters of instrumented frames (docs/commands.md "Counters"): per pixel, summed over all its
// rays, COUNTER_KINDS of them per pixel, COUNTER_<ID> each, as renderers/work_counter_list.h lists
// them. The kernels get that list as WORK_COUNTERS(X), X(ID, index) per counter, from the defines
// that renderers/vulkan/shader_compiler.cpp prepends to every kernel (work_counter_glsl_prelude());
// the C++ declares the same constants in namespace sdfbench, where their users are (gpu_types.h).
#ifndef __cplusplus
#ifndef WORK_COUNTERS
#error "no WORK_COUNTERS: compile the kernels with compile_shader() (renderers/vulkan/shader_compiler.h), which prepends them"
#endif
#define DECLARE_WORK_COUNTER(ID, index) const uint COUNTER_##ID = index;
WORK_COUNTERS(DECLARE_WORK_COUNTER)
#undef DECLARE_WORK_COUNTER
#define WORK_COUNTER_PLUS_ONE(ID, index) +1u
const uint COUNTER_KINDS = 0u WORK_COUNTERS(WORK_COUNTER_PLUS_ONE);
#undef WORK_COUNTER_PLUS_ONE
#endif
#define COUNTERS_BINDING 32  // the per-pixel counters buffer: past every backend's bindings (8 and up)

#define NO_INSTANCE 0xffffffffu     // the ray escaped to the sky
#define FLOOR_INSTANCE 0xfffffffeu  // the analytic floor plane, shared by every backend
#define NO_UV_TABLE 0xffffffffu     // GpuMaterial.image_texture.w: the hit's own uv

// Implicit objects (thesis 5.1, figure 6.5): a CSG tree per object, flattened to postfix nodes
// (renderers/implicit_tables.cpp), evaluated by implicit_trace.glsl. Kinds as ImplicitKind in
// scenes/implicit.h; primitives below IMPLICIT_UNION, binary operations from it on.
#define IMPLICIT_SPHERE 0u
#define IMPLICIT_BOX 1u
#define IMPLICIT_ELLIPSOID 2u
#define IMPLICIT_CAPSULE 3u
#define IMPLICIT_TORUS 4u
#define IMPLICIT_PLANE 5u
#define IMPLICIT_UNION 6u
#define IMPLICIT_INTERSECTION 7u
#define IMPLICIT_SUBTRACTION 8u
#define IMPLICIT_MAX_NODES 64u    // per object: bounds the evaluation loop (lavapipe's loop budget)
#define IMPLICIT_STACK_SIZE 8u    // postfix evaluation stack; the loader rejects deeper trees
#define IMPLICIT_MAX_STEPS 128u   // sphere-tracing steps per object and ray; a ray out of steps misses

struct GpuMaterial {
  vec4 albedo;          // rgb albedo; w: checker square size in uv units (0: no checker)
  vec4 checker_albedo;  // rgb: the checker's second colour; w: image texture repeat in uv units (0: none)
  vec4 optics;          // x: reflectance, y: transmission, z: index of refraction
  uvec4 image_texture;  // x: first texel in the texel table, y: width, z: height; w: the mesh's
                        // per-triangle uv table in the texel table (NO_UV_TABLE: none)
};

struct GpuLight {
  vec4 position;  // w = 0: directional light, xyz = unit direction towards it; w = 1: point light
  vec4 color;     // rgb radiance scale
};

struct FrameParams {
  vec4 camera_origin;
  vec4 camera_forward;  // unit viewing direction
  vec4 camera_right;    // scaled by tan(fov_y / 2) * aspect
  vec4 camera_up;       // scaled by tan(fov_y / 2)
  vec4 sky_zenith;
  vec4 sky_horizon;
  vec4 floor;    // x: height, y: material index, z: 1 when the floor exists
  vec4 tracing;  // x: unused, y: ambient, z: max ray distance, w: implicit hit epsilon
  uvec4 image;   // x: width, y: height, z: mode (MODE_*), w: light count
  uvec4 limits;  // x: whitted max recursion depth (capped at MAX_DEPTH_LIMIT), y: implicit objects
};

// One CSG node. Primitives are evaluated in their own frame (the node's placement in the object).
struct GpuImplicitNode {
  uvec4 info;       // x: kind (IMPLICIT_*)
  vec4 a;           // primitive parameters, as implicit_sdf.glsl reads them
  vec4 b;
  vec4 to_local0;   // object -> primitive frame: rows of a 3x4 affine map
  vec4 to_local1;
  vec4 to_local2;
};

// One implicit object: its node range, transform and object-space bounds.
struct GpuImplicitObject {
  vec4 bounds_min;  // object-space box around the shape; w: normal difference step (object units)
  vec4 bounds_max;  // w: the object's uniform scale (object distance x scale = world distance)
  vec4 to_object0;  // world -> object: rows of a 3x4 affine map
  vec4 to_object1;
  vec4 to_object2;
  vec4 to_world0;   // object -> world 3x3 (rotation x scale), rows: turns gradients into normals
  vec4 to_world1;
  vec4 to_world2;
  uvec4 info;       // x: first node, y: node count, z: material, w: instance id (after the meshes')
};

// A ray of the Whitted tree still to be traced.
struct PathEntry {
  vec4 origin;  // xyz; w: depth (0: the primary ray)
  vec4 dir;     // xyz, unit length
  vec4 weight;  // rgb: the ray's share of the pixel colour
};

// A pixel's progress besides its ray stack (shading.glsl); the Vulkan kernel keeps both in
// buffers between whitted passes.
struct PixelState {
  vec4 color;      // rgb: radiance gathered so far
  uvec4 counters;  // x: rays on the stack, y: rays traced
};

// Per-pixel output written by the kernels: the AOVs of the primary hit.
struct GpuAov {
  vec4 normal_depth;  // xyz: shading normal facing the camera, w: ray parameter t (0: miss)
  uvec4 ids;          // x: instance id, y: primitive id, z: rays traced for this pixel, w: CUT_* bits (render_main.glsl)
};

// Why a pixel was cut short (GpuAov ids.w; 0: it was not): the driver's per-invocation loop
// limit (docs/limits.md "The loop limit"), or the kernel's own hard bound on a traversal (a stack, an
// iteration count).
#define CUT_LOOP_CAP 1u
#define CUT_TRAVERSAL_BOUND 2u

struct Ray {
  vec3 origin;
  vec3 dir;
};

// What a backend's closest_hit reports; shading derives everything else from it.
struct Hit {
  float t;
  uint instance;
  uint prim;
  uint material;
  vec3 normal;  // world-space unit shading normal
  vec2 uv;
};

struct PixelAov {
  float depth;
  uint instance;
  uint prim;
  vec3 normal;
  uint rays;  // every ray this pixel traced (for Mrays/s)
};

// Barycentric interpolation with the Möller–Trumbore / Embree convention:
// p = (1 - u - v) * a + u * b + v * c.
SHARED_FN vec3 interpolate_barycentric(vec3 a, vec3 b, vec3 c, vec2 uv) {
  return (1.0f - uv.x - uv.y) * a + uv.x * b + uv.y * c;
}

#endif
