#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
// bvh: a BVH of 2, 4 or 8 children a node traversed in the compute kernel (bvh_builder.h: Embree's
// SAH builder; bvh_layouts.h: the node layouts). One node table holds every mesh's BVH and then
// the top level's; a top-level leaf is one entry (an instance and a node of its mesh's BVH: its
// root, or with --bvh-top rebraided a node opened into the top level), so the traversal is one
// loop over items (a node, and the instance whose frame it is in; TOP for top-level nodes). A
// visit tests all of a node's child boxes, tests the triangles of the leaves the ray enters, and
// goes on with the nearest inner child or entry, the others pushed farthest first with their
// entry distances and skipped when popped beyond the nearest hit. --bvh-top flat: one level over
// every triangle in world space (instance 0 of the tables is the identity; flat_ids names the
// real instance). Möller–Trumbore as tri-aabb, so hits agree with Embree to rounding. The stack
// holds BVH_STACK_SIZE items (the renderer sizes it by the trees' depths: a visit pushes at most
// width - 1, so it never overflows); the visits are bounded by the header's bound (each top node
// once, each entry's mesh nodes once), whatever the tables hold; BVH_VISIT_LIMIT (tests only)
// lowers it. Running out of either counts the pixel as cut short, never silently wrong.

#include "frame_bindings.glsl"
#include "triangle_tables.glsl"

#ifndef BVH_WIDTH
#define BVH_WIDTH 2
#endif
#ifndef BVH_QUANTISED
#define BVH_QUANTISED 0
#endif
#ifndef BVH_FLAT
#define BVH_FLAT 0
#endif
#define BVH_QUADS (BVH_WIDTH >= 4 ? BVH_WIDTH / 4 : 1)  // groups of 4 children (one vec4 of boxes each)
#define BVH_AILA_LAINE (BVH_WIDTH == 2 && BVH_QUANTISED == 0)
#if BVH_AILA_LAINE
#define BVH_NODE_TEXELS 4
#elif BVH_QUANTISED
#define BVH_NODE_TEXELS (2 + (6 * BVH_QUADS + 3) / 4)
#else
#define BVH_NODE_TEXELS (1 + 6 * BVH_QUADS)
#endif

layout(binding = 11) uniform utextureBuffer bvh_nodes;    // the meshes' BVHs, then the top level's
layout(binding = 12) uniform utextureBuffer bvh_entries;  // texel 0: (top root, visit bound); then (instance, mesh node) per top-level reference
layout(binding = 13) uniform utextureBuffer flat_ids;     // --bvh-top flat: (instance, triangle, material) per triangle slot

bool traversal_cut = false;
#define TRAVERSAL_OVERFLOW traversal_cut

const float MISS = 3.4e38f;
const uint TOP = 0xFFFFFFFFu;  // the instance of a top-level item: the ray in world space

// Does the ray enter a child (its entry from box_entries) before tmax? MISS never does, also when
// tmax is not below it.
bool enters(float t, float tmax) {
  return t <= tmax && t < MISS;
}

// Where the ray enters each of 4 boxes within [0, tmax] (o_inv = origin * inv_dir), or MISS.
vec4 box_entries(vec4 lox, vec4 loy, vec4 loz, vec4 hix, vec4 hiy, vec4 hiz, vec3 inv_dir, vec3 o_inv, float tmax) {
  vec4 x0 = lox * inv_dir.x - o_inv.x, x1 = hix * inv_dir.x - o_inv.x;
  vec4 y0 = loy * inv_dir.y - o_inv.y, y1 = hiy * inv_dir.y - o_inv.y;
  vec4 z0 = loz * inv_dir.z - o_inv.z, z1 = hiz * inv_dir.z - o_inv.z;
  vec4 enter = max(max(min(x0, x1), min(y0, y1)), max(min(z0, z1), vec4(0.0f)));
  vec4 leave = min(min(max(x0, x1), max(y0, y1)), min(max(z0, z1), vec4(tmax)));
  return mix(vec4(MISS), enter, lessThanEqual(enter, leave));
}

// Every child slot of a node, unrolled (the kernel indexes its per-child values by constants
// only: lavapipe keeps them in registers, where a variable index would spill them).
#if BVH_WIDTH == 2
#define EACH_CHILD(X) X(0) X(1)
#elif BVH_WIDTH == 4
#define EACH_CHILD(X) X(0) X(1) X(2) X(3)
#else
#define EACH_CHILD(X) X(0) X(1) X(2) X(3) X(4) X(5) X(6) X(7)
#endif

// A visited node: each child's entry distance (MISS: not entered, or an empty slot), and the
// node's links, from which a child's index and count follow (child_link).
struct Node {
  float t[BVH_WIDTH];
  uvec4 links;  // Aila-Laine: (child 0, child 1, count 0, count 1); wide: (first inner child, first reference, 8 meta bytes)
};

// Child k's index (an inner node, or a leaf's first reference) and count (0: an inner node).
void child_link(uvec4 links, int k, out uint index, out uint count) {
#if BVH_AILA_LAINE
  index = k == 0 ? links.x : links.y;
  count = k == 0 ? links.z : links.w;
#else
  uint meta = ((k < 4 ? links.z : links.w) >> (8 * (k & 3))) & 0xFFu;
  uint kind = meta >> 5;
  count = kind == 7u ? 0u : kind;
  index = (kind == 7u ? links.x : links.y) + (meta & 31u);
#endif
}

#if BVH_AILA_LAINE
void decode(uint n, vec3 inv_dir, vec3 o_inv, float tmax, out Node node) {
  int base = 4 * int(n);
  uvec4 a = texelFetch(bvh_nodes, base), b = texelFetch(bvh_nodes, base + 1);
  uvec4 p = texelFetch(bvh_nodes, base + 2), q = texelFetch(bvh_nodes, base + 3);
  vec4 t = box_entries(vec4(uintBitsToFloat(a.x), uintBitsToFloat(p.x), 0, 0), vec4(uintBitsToFloat(a.y), uintBitsToFloat(p.y), 0, 0),
                       vec4(uintBitsToFloat(a.z), uintBitsToFloat(p.z), 0, 0), vec4(uintBitsToFloat(b.x), uintBitsToFloat(q.x), 0, 0),
                       vec4(uintBitsToFloat(b.y), uintBitsToFloat(q.y), 0, 0), vec4(uintBitsToFloat(b.z), uintBitsToFloat(q.z), 0, 0),
                       inv_dir, o_inv, tmax);
  node.t[0] = t.x;
  node.t[1] = t.y;
  node.links = uvec4(a.w, b.w, p.w, q.w);
}
#else
vec4 unpack_bytes(uint w) { return vec4(uvec4(w, w >> 8, w >> 16, w >> 24) & 0xFFu); }

void decode(uint n, vec3 inv_dir, vec3 o_inv, float tmax, out Node node) {
  int base = BVH_NODE_TEXELS * int(n);
  node.links = texelFetch(bvh_nodes, base);
#if BVH_QUANTISED
  uvec4 h = texelFetch(bvh_nodes, base + 1);  // the grid's corner and exponents
  vec3 origin = uintBitsToFloat(h.xyz);
  vec3 scale = uintBitsToFloat((uvec3(h.w, h.w >> 8, h.w >> 16) & 0xFFu) << 23u);  // 2^e, e biased by 127
  uvec4 w0 = texelFetch(bvh_nodes, base + 2), w1 = texelFetch(bvh_nodes, base + 3);
#if BVH_WIDTH == 8
  uvec4 w2 = texelFetch(bvh_nodes, base + 4);
  // words: lo.x lo.x lo.y lo.y lo.z lo.z hi.x hi.x hi.y hi.y hi.z hi.z (children 0-3, 4-7)
  uint lx[2] = uint[2](w0.x, w0.y), ly[2] = uint[2](w0.z, w0.w), lz[2] = uint[2](w1.x, w1.y);
  uint hx[2] = uint[2](w1.z, w1.w), hy[2] = uint[2](w2.x, w2.y), hz[2] = uint[2](w2.z, w2.w);
#else
  uint lx[1] = uint[1](w0.x), ly[1] = uint[1](w0.y), lz[1] = uint[1](w0.z);
  uint hx[1] = uint[1](w0.w), hy[1] = uint[1](w1.x), hz[1] = uint[1](w1.y);
#endif
#endif
  for (int q = 0; q < BVH_QUADS; ++q) {
#if BVH_QUANTISED
    vec4 t = box_entries(origin.x + unpack_bytes(lx[q]) * scale.x, origin.y + unpack_bytes(ly[q]) * scale.y,
                         origin.z + unpack_bytes(lz[q]) * scale.z, origin.x + unpack_bytes(hx[q]) * scale.x,
                         origin.y + unpack_bytes(hy[q]) * scale.y, origin.z + unpack_bytes(hz[q]) * scale.z, inv_dir, o_inv, tmax);
#else
    vec4 t = box_entries(uintBitsToFloat(texelFetch(bvh_nodes, base + 1 + q)),
                         uintBitsToFloat(texelFetch(bvh_nodes, base + 1 + BVH_QUADS + q)),
                         uintBitsToFloat(texelFetch(bvh_nodes, base + 1 + 2 * BVH_QUADS + q)),
                         uintBitsToFloat(texelFetch(bvh_nodes, base + 1 + 3 * BVH_QUADS + q)),
                         uintBitsToFloat(texelFetch(bvh_nodes, base + 1 + 4 * BVH_QUADS + q)),
                         uintBitsToFloat(texelFetch(bvh_nodes, base + 1 + 5 * BVH_QUADS + q)), inv_dir, o_inv, tmax);
#endif
    if (q == 0) {
      node.t[0] = t.x;
      node.t[1] = t.y;
#if BVH_WIDTH >= 4
      node.t[2] = t.z;
      node.t[3] = t.w;
#endif
    }
#if BVH_WIDTH == 8
    if (q == 1) {
      node.t[4] = t.x;
      node.t[5] = t.y;
      node.t[6] = t.z;
      node.t[7] = t.w;
    }
#endif
  }
#define EMPTY_SLOT(k) if ((((k < 4 ? node.links.z : node.links.w) >> (8 * (k & 3))) & 0xFFu) == 0u) node.t[k] = MISS;
  EACH_CHILD(EMPTY_SLOT)
#undef EMPTY_SLOT
}
#endif

// The nearer of two (t, node, item) candidates into slot a.
#define ORDER(a, b)                                        \
  if (key[b] < key[a]) {                                   \
    float kt = key[a]; key[a] = key[b]; key[b] = kt;       \
    uint kn = next[a]; next[a] = next[b]; next[b] = kn;    \
    uint ki = owner[a]; owner[a] = owner[b]; owner[b] = ki; \
  }
#if BVH_WIDTH == 2
#define SORT_CANDIDATES ORDER(0, 1)
#elif BVH_WIDTH == 4
#define SORT_CANDIDATES ORDER(0, 1) ORDER(2, 3) ORDER(0, 2) ORDER(1, 3) ORDER(1, 2)
#else  // Batcher's odd-even merge sort of 8: 19 comparators
#define SORT_CANDIDATES                                                                                       \
  ORDER(0, 1) ORDER(2, 3) ORDER(4, 5) ORDER(6, 7) ORDER(0, 2) ORDER(1, 3) ORDER(4, 6) ORDER(5, 7) ORDER(1, 2) \
  ORDER(5, 6) ORDER(0, 4) ORDER(1, 5) ORDER(2, 6) ORDER(3, 7) ORDER(2, 4) ORDER(3, 5) ORDER(1, 2) ORDER(3, 4) ORDER(5, 6)
#endif

// The scene's nearest (or, for `any`, some) triangle hit with t < tmax: its instance (of the
// tables), slot and uv.
bool trace_scene(Ray ray, bool any, inout float tmax, out uint inst, out uint slot, out vec2 uv) {
  uvec4 header = texelFetch(bvh_entries, 0);
#ifdef BVH_VISIT_LIMIT
  const uint visit_bound = min(header.y, BVH_VISIT_LIMIT);
#else
  const uint visit_bound = header.y;
#endif
  uint node = header.x;
  uint item = BVH_FLAT != 0 ? 0u : TOP;  // the current node's instance
  uint frame = item;                     // whose frame o, d are in
  vec3 o = ray.origin, d = ray.dir;
  vec3 inv_dir = safe_inverse(d);
  vec3 o_inv = o * inv_dir;
  uint stack_node[BVH_STACK_SIZE];
  uint stack_item[BVH_STACK_SIZE];
  float stack_t[BVH_STACK_SIZE];
  uint sp = 0u;
  bool found = false;
  inst = NO_INSTANCE;
  slot = 0u;
  uv = vec2(0.0f);
  for (uint visits = 0u;; ++visits) {
    if (visits >= visit_bound) {
      traversal_cut = true;
      break;
    }
    if (item != frame) {
      frame = item;
      o = item == TOP ? ray.origin : vec3(instances[item].world_to_object * vec4(ray.origin, 1.0f));
      d = item == TOP ? ray.dir : vec3(instances[item].world_to_object * vec4(ray.dir, 0.0f));
      inv_dir = safe_inverse(d);
      o_inv = o * inv_dir;
    }
    COUNT(COUNTER_NODE_VISITS, 1u);
    COUNT(COUNTER_AABB_TESTS, uint(BVH_WIDTH));
    Node n;
    decode(node, inv_dir, o_inv, tmax, n);
    // Candidates: entered inner children, and top-level leaves as their entries' items; the
    // entered mesh leaves are tested now (leaf_mask).
    float key[BVH_WIDTH];
    uint next[BVH_WIDTH], owner[BVH_WIDTH];
    uint leaf_mask = 0u;
#define CANDIDATE(k)                                                  \
  {                                                                   \
    uint index, count;                                                \
    child_link(n.links, k, index, count);                             \
    bool inside = enters(n.t[k], tmax);                                  \
    key[k] = inside ? n.t[k] : MISS;                                     \
    next[k] = index;                                                  \
    owner[k] = item;                                                  \
    if (count != 0u) {                                                \
      if (item == TOP && inside) {                                       \
        uvec4 entry = texelFetch(bvh_entries, 1 + int(index));        \
        next[k] = entry.y;                                            \
        owner[k] = entry.x;                                           \
      } else {                                                        \
        if (inside) leaf_mask |= 1u << k;                                \
        key[k] = MISS;                                                \
      }                                                               \
    }                                                                 \
  }
    EACH_CHILD(CANDIDATE)
#undef CANDIDATE
    if (leaf_mask != 0u) {
      int first = int(instances[item].info.x);
      while (leaf_mask != 0u) {
        int k = findLSB(leaf_mask);
        leaf_mask &= leaf_mask - 1u;
        uint index, count;
        child_link(n.links, k, index, count);
        for (uint r = index; r < index + count; ++r) {
          float t;
          vec2 bary;
          if (hits_triangle(o, d, 3 * (first + int(r)), tmax, t, bary)) {
            tmax = t;
            inst = item;
            slot = r;
            uv = bary;
            found = true;
            if (any) return true;
          }
        }
      }
#define BEYOND_HIT(k) if (key[k] > tmax) key[k] = MISS;
      EACH_CHILD(BEYOND_HIT)
#undef BEYOND_HIT
    }
    SORT_CANDIDATES
    // The nearest goes on; the others wait, farthest deepest.
#define PUSH(k)                            \
  if (k > 0 && key[k] < MISS) {            \
    if (sp < BVH_STACK_SIZE) {             \
      stack_node[sp] = next[k];            \
      stack_item[sp] = owner[k];           \
      stack_t[sp] = key[k];                \
      ++sp;                                \
    } else {                               \
      traversal_cut = true;                \
    }                                      \
  }
#if BVH_WIDTH == 8
    PUSH(7) PUSH(6) PUSH(5) PUSH(4)
#endif
#if BVH_WIDTH >= 4
    PUSH(3) PUSH(2)
#endif
    PUSH(1)
#undef PUSH
    if (key[0] < MISS) {
      node = next[0];
      item = owner[0];
      continue;
    }
    // Pop the next item the ray still enters before the nearest hit.
    bool resume = false;
    while (sp > 0u && !resume) {
      --sp;
      resume = enters(stack_t[sp], tmax);
      node = stack_node[sp];
      item = stack_item[sp];
    }
    if (!resume) break;
  }
  return found;
}

bool closest_hit(Ray ray, float tmax, out Hit hit) {
  float t = tmax;
  uint inst, slot;
  vec2 uv;
  if (!trace_scene(ray, false, t, inst, slot, uv)) return false;
  fill_triangle_hit(inst, slot, uv, t, hit);
#if BVH_FLAT
  uvec4 id = texelFetch(flat_ids, int(slot));  // the table's one instance is the identity
  hit.instance = id.x;
  hit.prim = id.y;
  hit.material = id.z;
#endif
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
