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

// A node's children: entry distance (MISS: not entered, or an empty slot), and an inner node's
// index (count 0) or a leaf's first reference and count.
struct Children {
  float t[BVH_WIDTH];
  uint node[BVH_WIDTH];
  uint count[BVH_WIDTH];
};

#if BVH_AILA_LAINE
void decode(uint n, vec3 inv_dir, vec3 o_inv, float tmax, out Children c) {
  int base = 4 * int(n);
  uvec4 a = texelFetch(bvh_nodes, base), b = texelFetch(bvh_nodes, base + 1);
  uvec4 p = texelFetch(bvh_nodes, base + 2), q = texelFetch(bvh_nodes, base + 3);
  vec4 t = box_entries(vec4(uintBitsToFloat(a.x), uintBitsToFloat(p.x), 0, 0), vec4(uintBitsToFloat(a.y), uintBitsToFloat(p.y), 0, 0),
                       vec4(uintBitsToFloat(a.z), uintBitsToFloat(p.z), 0, 0), vec4(uintBitsToFloat(b.x), uintBitsToFloat(q.x), 0, 0),
                       vec4(uintBitsToFloat(b.y), uintBitsToFloat(q.y), 0, 0), vec4(uintBitsToFloat(b.z), uintBitsToFloat(q.z), 0, 0),
                       inv_dir, o_inv, tmax);
  c.t[0] = t.x;
  c.t[1] = t.y;
  c.node[0] = a.w;
  c.node[1] = b.w;
  c.count[0] = p.w;
  c.count[1] = q.w;
}
#else
vec4 unpack_bytes(uint w) { return vec4(uvec4(w, w >> 8, w >> 16, w >> 24) & 0xFFu); }

void decode(uint n, vec3 inv_dir, vec3 o_inv, float tmax, out Children c) {
  int base = BVH_NODE_TEXELS * int(n);
  uvec4 info = texelFetch(bvh_nodes, base);  // first inner child, first reference, 8 meta bytes
#if BVH_QUANTISED
  uvec4 h = texelFetch(bvh_nodes, base + 1);  // the grid's corner and exponents
  vec3 origin = uintBitsToFloat(h.xyz);
  vec3 scale = uintBitsToFloat((uvec3(h.w, h.w >> 8, h.w >> 16) & 0xFFu) << 23u);  // 2^e, e biased by 127
  uint words[4 * ((6 * BVH_QUADS + 3) / 4)];
  for (int i = 0; i < (6 * BVH_QUADS + 3) / 4; ++i) {
    uvec4 w = texelFetch(bvh_nodes, base + 2 + i);
    words[4 * i] = w.x;
    words[4 * i + 1] = w.y;
    words[4 * i + 2] = w.z;
    words[4 * i + 3] = w.w;
  }
#endif
  for (int q = 0; q < BVH_QUADS; ++q) {
#if BVH_QUANTISED
    vec4 lox = origin.x + unpack_bytes(words[q]) * scale.x;
    vec4 loy = origin.y + unpack_bytes(words[BVH_QUADS + q]) * scale.y;
    vec4 loz = origin.z + unpack_bytes(words[2 * BVH_QUADS + q]) * scale.z;
    vec4 hix = origin.x + unpack_bytes(words[3 * BVH_QUADS + q]) * scale.x;
    vec4 hiy = origin.y + unpack_bytes(words[4 * BVH_QUADS + q]) * scale.y;
    vec4 hiz = origin.z + unpack_bytes(words[5 * BVH_QUADS + q]) * scale.z;
#else
    vec4 lox = uintBitsToFloat(texelFetch(bvh_nodes, base + 1 + q));
    vec4 loy = uintBitsToFloat(texelFetch(bvh_nodes, base + 1 + BVH_QUADS + q));
    vec4 loz = uintBitsToFloat(texelFetch(bvh_nodes, base + 1 + 2 * BVH_QUADS + q));
    vec4 hix = uintBitsToFloat(texelFetch(bvh_nodes, base + 1 + 3 * BVH_QUADS + q));
    vec4 hiy = uintBitsToFloat(texelFetch(bvh_nodes, base + 1 + 4 * BVH_QUADS + q));
    vec4 hiz = uintBitsToFloat(texelFetch(bvh_nodes, base + 1 + 5 * BVH_QUADS + q));
#endif
    vec4 t = box_entries(lox, loy, loz, hix, hiy, hiz, inv_dir, o_inv, tmax);
    for (int j = 0; j < 4 && 4 * q + j < BVH_WIDTH; ++j) c.t[4 * q + j] = t[j];
  }
  for (int k = 0; k < BVH_WIDTH; ++k) {
    uint meta = (info[2 + k / 4] >> (8 * (k % 4))) & 0xFFu;
    uint kind = meta >> 5;
    c.count[k] = kind == 7u ? 0u : kind;
    c.node[k] = (kind == 7u ? info.x : info.y) + (meta & 31u);
    if (meta == 0u) c.t[k] = MISS;
  }
}
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
    Children c;
    decode(node, inv_dir, o_inv, tmax, c);
    uint child_item[BVH_WIDTH];
    for (int k = 0; k < BVH_WIDTH; ++k) {
      child_item[k] = item;
      if (c.count[k] == 0u || !enters(c.t[k], tmax)) continue;
      if (item == TOP) {  // a top-level leaf: its entry is an item in its instance's frame
        uvec4 entry = texelFetch(bvh_entries, 1 + int(c.node[k]));
        child_item[k] = entry.x;
        c.node[k] = entry.y;
        c.count[k] = 0u;
        continue;
      }
      int first = int(instances[item].info.x);
      for (uint r = c.node[k]; r < c.node[k] + c.count[k]; ++r) {
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
      c.t[k] = MISS;
    }
    // The entered inner children and entries, nearest first.
    int order[BVH_WIDTH];
    int entered = 0;
    for (int k = 0; k < BVH_WIDTH; ++k) {
      if (c.count[k] != 0u || !enters(c.t[k], tmax)) continue;
      int at = entered++;
      while (at > 0 && c.t[order[at - 1]] > c.t[k]) {
        order[at] = order[at - 1];
        --at;
      }
      order[at] = k;
    }
    if (entered > 0) {
      for (int i = entered - 1; i > 0; --i) {
        if (sp < BVH_STACK_SIZE) {
          stack_node[sp] = c.node[order[i]];
          stack_item[sp] = child_item[order[i]];
          stack_t[sp] = c.t[order[i]];
          ++sp;
        } else {
          traversal_cut = true;
        }
      }
      node = c.node[order[0]];
      item = child_item[order[0]];
      continue;
    }
    // Pop the next item the ray still enters before the nearest hit.
    bool next = false;
    while (sp > 0u && !next) {
      --sp;
      next = enters(stack_t[sp], tmax);
      node = stack_node[sp];
      item = stack_item[sp];
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
