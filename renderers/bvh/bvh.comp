#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
// bvh: a two-level BVH traversed in the compute kernel (bvh_builder.h: Embree's SAH builder,
// the node layout of Aila & Laine 2009). The top level holds the instances' world boxes, one
// instance per leaf; at a leaf the ray goes into the instance's frame and down its mesh's BVH.
// Both levels test a node's two child boxes together and descend into the nearer one, the
// farther one pushed with its entry distance, and skipped when popped beyond the nearest hit.
// Möller–Trumbore as tri-aabb, so hits agree with Embree to rounding. A level's stack holds
// BVH_STACK_SIZE entries, defined by the renderer as the scene's deepest BVH rounded up to 8 (so
// that scenes share kernels): a traversal pushes at most one entry per level it descends, so it
// never overflows. A traversal visits each node at most once, so it stops after as many visits as
// its level's table holds nodes (read from the table: no per-scene kernel), whatever the data
// holds; BVH_VISIT_LIMIT (tests only) lowers that. Running out of either would count the pixel as
// cut short, never silently wrong.

#include "frame_bindings.glsl"
#include "triangle_tables.glsl"

layout(binding = 11) uniform textureBuffer mesh_nodes;  // every mesh's BVH (root: TriInstance info.w), 4 texels a node
layout(binding = 12) uniform textureBuffer top_nodes;   // the instances' BVH, root 0

bool traversal_cut = false;
#define TRAVERSAL_OVERFLOW traversal_cut

const float MISS = 3.4e38f;

// The most node visits a traversal of a table may make: its node count (4 texels a node).
uint visit_bound(uint nodes) {
#ifdef BVH_VISIT_LIMIT
  return min(nodes, BVH_VISIT_LIMIT);
#else
  return nodes;
#endif
}

// Does the ray enter a child (its entry from box_entry) before tmax? MISS never does, also when
// tmax is not below it.
bool enters(float t, float tmax) {
  return t <= tmax && t < MISS;
}

// Where the ray enters the box within [0, tmax] (o_inv = origin * inv_dir), or MISS.
float box_entry(vec3 lo, vec3 hi, vec3 inv_dir, vec3 o_inv, float tmax) {
  vec3 t0 = lo * inv_dir - o_inv;
  vec3 t1 = hi * inv_dir - o_inv;
  vec3 near = min(t0, t1);
  vec3 far = max(t0, t1);
  float enter = max(max(near.x, near.y), max(near.z, 0.0f));
  float leave = min(min(far.x, far.y), min(far.z, tmax));
  return enter <= leave ? enter : MISS;
}

// One node of either level: its two children's entries, indices and counts (0: an inner node).
struct NodeVisit {
  float t[2];
  uint child[2];
  uint count[2];
};

NodeVisit visit(vec4 a, vec4 b, vec4 c, vec4 d, vec3 inv_dir, vec3 o_inv, float tmax) {
  COUNT(COUNTER_AABB_TESTS, 2u);
  NodeVisit v;
  v.t[0] = box_entry(a.xyz, b.xyz, inv_dir, o_inv, tmax);
  v.t[1] = box_entry(c.xyz, d.xyz, inv_dir, o_inv, tmax);
  v.child[0] = floatBitsToUint(a.w);
  v.child[1] = floatBitsToUint(b.w);
  v.count[0] = floatBitsToUint(c.w);
  v.count[1] = floatBitsToUint(d.w);
  return v;
}

// The nearest (or, for `any`, some) triangle of instance `inst` with t < tmax, the ray in the
// instance's frame; tmax, slot and uv are updated on a hit. visit_limit: visit_bound of the mesh table.
bool trace_mesh(uint inst, vec3 o, vec3 d, bool any, uint visit_limit, inout float tmax, inout uint slot, inout vec2 uv) {
  vec3 inv_dir = safe_inverse(d);
  vec3 o_inv = o * inv_dir;
  int first = int(instances[inst].info.x);
  uint stack_node[BVH_STACK_SIZE];
  float stack_t[BVH_STACK_SIZE];
  uint sp = 0u;
  uint node = instances[inst].info.w;
  bool found = false;
  for (uint visits = 0u;; ++visits) {
    if (visits == visit_limit) {
      traversal_cut = true;
      break;
    }
    int base = 4 * int(node);
    NodeVisit v = visit(texelFetch(mesh_nodes, base), texelFetch(mesh_nodes, base + 1), texelFetch(mesh_nodes, base + 2),
                        texelFetch(mesh_nodes, base + 3), inv_dir, o_inv, tmax);
    // Leaves now (they are never pushed); an inner child waits for the decision below.
    for (int k = 0; k < 2; ++k) {
      if (v.count[k] == 0u || !enters(v.t[k], tmax)) continue;
      for (uint r = v.child[k]; r < v.child[k] + v.count[k]; ++r) {
        float t;
        vec2 bary;
        if (hits_triangle(o, d, 3 * (first + int(r)), tmax, t, bary)) {
          tmax = t;
          slot = r;
          uv = bary;
          found = true;
          if (any) return true;
        }
      }
      v.t[k] = MISS;
    }
    bool hit0 = enters(v.t[0], tmax), hit1 = enters(v.t[1], tmax);
    if (hit0 && hit1) {
      uint near = v.t[0] <= v.t[1] ? 0u : 1u;
      if (sp < BVH_STACK_SIZE) {
        stack_node[sp] = v.child[1u - near];
        stack_t[sp] = v.t[1u - near];
        ++sp;
      } else {
        traversal_cut = true;
      }
      node = v.child[near];
      continue;
    }
    if (hit0 || hit1) {
      node = v.child[hit0 ? 0 : 1];
      continue;
    }
    // Pop the next subtree the ray still enters before the nearest hit.
    bool next = false;
    while (sp > 0u && !next) {
      --sp;
      next = enters(stack_t[sp], tmax);
      node = stack_node[sp];
    }
    if (!next) break;
  }
  return found;
}

// The scene's nearest (or some) triangle hit with t < tmax: its instance, slot and uv.
bool trace_scene(Ray ray, bool any, inout float tmax, out uint inst, out uint slot, out vec2 uv) {
  vec3 inv_dir = safe_inverse(ray.dir);
  vec3 o_inv = ray.origin * inv_dir;
  uint stack_node[BVH_STACK_SIZE];
  float stack_t[BVH_STACK_SIZE];
  uint sp = 0u;
  uint node = 0u;
  bool found = false;
  inst = NO_INSTANCE;
  slot = 0u;
  uv = vec2(0.0f);
  const uint visit_limit = visit_bound(uint(textureSize(top_nodes)) / 4u);
  const uint mesh_visit_limit = visit_bound(uint(textureSize(mesh_nodes)) / 4u);  // once a ray, not once an instance
  for (uint visits = 0u;; ++visits) {
    if (visits == visit_limit) {
      traversal_cut = true;
      break;
    }
    int base = 4 * int(node);
    NodeVisit v = visit(texelFetch(top_nodes, base), texelFetch(top_nodes, base + 1), texelFetch(top_nodes, base + 2),
                        texelFetch(top_nodes, base + 3), inv_dir, o_inv, tmax);
    for (int k = 0; k < 2; ++k) {
      if (v.count[k] == 0u || !enters(v.t[k], tmax)) continue;
      uint i = v.child[k];  // a leaf: one instance
      vec3 o = vec3(instances[i].world_to_object * vec4(ray.origin, 1.0f));
      vec3 d = vec3(instances[i].world_to_object * vec4(ray.dir, 0.0f));
      if (trace_mesh(i, o, d, any, mesh_visit_limit, tmax, slot, uv)) {
        inst = i;
        found = true;
        if (any) return true;
      }
      v.t[k] = MISS;
    }
    bool hit0 = enters(v.t[0], tmax), hit1 = enters(v.t[1], tmax);
    if (hit0 && hit1) {
      uint near = v.t[0] <= v.t[1] ? 0u : 1u;
      if (sp < BVH_STACK_SIZE) {
        stack_node[sp] = v.child[1u - near];
        stack_t[sp] = v.t[1u - near];
        ++sp;
      } else {
        traversal_cut = true;
      }
      node = v.child[near];
      continue;
    }
    if (hit0 || hit1) {
      node = v.child[hit0 ? 0 : 1];
      continue;
    }
    bool next = false;
    while (sp > 0u && !next) {
      --sp;
      next = enters(stack_t[sp], tmax);
      node = stack_node[sp];
    }
    if (!next) break;
  }
  return found;
}

bool closest_hit(Ray ray, float tmax, out Hit hit) {
  float t = tmax;
  uint inst, slot;
  vec2 uv;
  if (!trace_scene(ray, false, t, inst, slot, uv)) return false;
  fill_triangle_hit(inst, slot, uv, t, hit);
  return true;
}

float mesh_hit_tolerance() { return 0.0f; }  // ray-triangle hits lie on the triangle

bool any_hit(Ray ray, float tmax) {
  float t = tmax;
  uint inst, slot;
  vec2 uv;
  return trace_scene(ray, true, t, inst, slot, uv);
}

#include "render_main.glsl"
