#include "renderers/bvh/bvh_layouts.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "util/error.h"

namespace sdfbench {
namespace {

uint32_t bits(float f) { return glm::floatBitsToUint(f); }

// Children per uint of a quantised coordinate (a byte each), and uints per coordinate.
uint32_t quantised_uints(uint32_t width) { return std::max(1u, width / 4u); }


BvhLayout encode_binary(const BvhTree& tree, uint32_t node_base) {
  BvhLayout out;
  out.texels_per_node = 4;
  out.references = tree.references;
  out.node_of_tree.resize(tree.nodes.size());
  out.texels.reserve(4 * tree.nodes.size());
  for (size_t n = 0; n < tree.nodes.size(); ++n) {
    out.node_of_tree[n] = static_cast<uint32_t>(n);
    BvhChild c[2];
    for (uint32_t k = 0; k < 2; ++k) {
      if (k < tree.nodes[n].child_count) {
        c[k] = tree.nodes[n].children[k];
        if (!c[k].leaf()) c[k].index += node_base;
      } else {  // empty: a point at (FLT_MAX, FLT_MAX, FLT_MAX), which no ray reaches within its tmax
        c[k].box.min = c[k].box.max = glm::vec3(std::numeric_limits<float>::max());
        c[k].index = 0;
        c[k].count = 1;
      }
    }
    out.texels.push_back({bits(c[0].box.min.x), bits(c[0].box.min.y), bits(c[0].box.min.z), c[0].index});
    out.texels.push_back({bits(c[0].box.max.x), bits(c[0].box.max.y), bits(c[0].box.max.z), c[1].index});
    out.texels.push_back({bits(c[1].box.min.x), bits(c[1].box.min.y), bits(c[1].box.min.z), c[0].count});
    out.texels.push_back({bits(c[1].box.max.x), bits(c[1].box.max.y), bits(c[1].box.max.z), c[1].count});
  }
  return out;
}

// The kernel's decoding of a quantised bound: origin + q * 2^e, in float arithmetic (q * 2^e is exact).
float dequantise(float origin, uint32_t q, float scale) { return origin + static_cast<float>(q) * scale; }

// The exponent of an axis: the smallest step 2^e whose 255 steps from `origin` reach `hi`.
int axis_exponent(float origin, float hi) {
  const float extent = hi - origin;
  int e = -126;
  if (extent > 0.0f) {
    int exponent = 0;
    std::frexp(extent / 255.0f, &exponent);  // extent / 255 < 2^exponent
    e = std::max(exponent - 1, -126);
  }
  while (e < 127 && dequantise(origin, 255, std::ldexp(1.0f, e)) < hi) ++e;
  return e;
}

struct QuantisedBox {
  glm::uvec3 lo{255}, hi{0};
};

QuantisedBox quantise(const Aabb& box, const glm::vec3& origin, const glm::vec3& scale) {
  QuantisedBox q;
  for (int a = 0; a < 3; ++a) {
    auto lo = static_cast<uint32_t>(std::clamp(std::floor((box.min[a] - origin[a]) / scale[a]), 0.0f, 255.0f));
    while (lo > 0 && dequantise(origin[a], lo, scale[a]) > box.min[a]) --lo;
    auto hi = static_cast<uint32_t>(std::clamp(std::ceil((box.max[a] - origin[a]) / scale[a]), 0.0f, 255.0f));
    while (hi < 255 && dequantise(origin[a], hi, scale[a]) < box.max[a]) ++hi;
    q.lo[a] = lo;
    q.hi[a] = hi;
  }
  return q;
}

BvhLayout encode_wide(const BvhTree& tree, BvhNodes nodes, uint32_t node_base) {
  const uint32_t width = tree.width;
  BvhLayout out;
  out.texels_per_node = texels_per_node(width, nodes);
  out.node_of_tree.assign(tree.nodes.size(), 0);
  // Breadth-first: a node's inner children take the next consecutive layout indices.
  std::vector<uint32_t> order{0};
  order.reserve(tree.nodes.size());
  out.texels.reserve(static_cast<size_t>(out.texels_per_node) * tree.nodes.size());
  for (size_t i = 0; i < order.size(); ++i) {
    const BvhTreeNode& node = tree.nodes[order[i]];
    out.node_of_tree[order[i]] = static_cast<uint32_t>(i);
    const uint32_t inner_base = static_cast<uint32_t>(order.size());
    const uint32_t ref_base = static_cast<uint32_t>(out.references.size());
    uint32_t meta[kMaxBvhWidth] = {};
    Aabb node_box;
    for (uint32_t k = 0, inner = 0; k < node.child_count; ++k) {
      const BvhChild& c = node.children[k];
      node_box.extend(c.box);
      if (!c.leaf()) {
        meta[k] = kMetaInner << 5 | inner++;
        order.push_back(c.index);
        continue;
      }
      const uint32_t offset = static_cast<uint32_t>(out.references.size()) - ref_base;
      if (c.count > kMaxWideLeaf || offset > 31)
        throw InternalError("bvh: a leaf of " + std::to_string(c.count) + " references at offset " + std::to_string(offset));
      meta[k] = c.count << 5 | offset;
      out.references.insert(out.references.end(), tree.references.begin() + c.index,
                            tree.references.begin() + c.index + c.count);
    }
    glm::uvec4 info{inner_base + node_base, ref_base, 0, 0};
    for (uint32_t k = 0; k < kMaxBvhWidth; ++k) info[2 + k / 4] |= meta[k] << (8 * (k % 4));
    out.texels.push_back(info);

    const auto child_box = [&](uint32_t k) {
      Aabb b;
      if (k < node.child_count) return node.children[k].box;
      b.min = b.max = glm::vec3(std::numeric_limits<float>::max());
      return b;
    };
    if (nodes == BvhNodes::Float) {
      for (uint32_t coordinate = 0; coordinate < 6; ++coordinate)
        for (uint32_t q = 0; q < width / 4; ++q) {
          glm::uvec4 t;
          for (uint32_t j = 0; j < 4; ++j) {
            const Aabb b = child_box(4 * q + j);
            t[j] = bits(coordinate < 3 ? b.min[coordinate] : b.max[coordinate - 3]);
          }
          out.texels.push_back(t);
        }
      continue;
    }
    if (node_box.empty()) node_box.min = node_box.max = glm::vec3(0.0f);
    glm::ivec3 e;
    glm::vec3 scale;
    for (int a = 0; a < 3; ++a) {
      e[a] = axis_exponent(node_box.min[a], node_box.max[a]);
      scale[a] = std::ldexp(1.0f, e[a]);
    }
    out.texels.push_back({bits(node_box.min.x), bits(node_box.min.y), bits(node_box.min.z),
                          uint32_t(e.x + 127) | uint32_t(e.y + 127) << 8 | uint32_t(e.z + 127) << 16});
    const uint32_t per = quantised_uints(width);
    std::vector<uint32_t> words(6 * per, 0);
    for (uint32_t k = 0; k < node.child_count; ++k) {
      const QuantisedBox q = quantise(node.children[k].box, node_box.min, scale);
      for (uint32_t coordinate = 0; coordinate < 6; ++coordinate) {
        const uint32_t value = coordinate < 3 ? q.lo[coordinate] : q.hi[coordinate - 3];
        words[coordinate * per + k / 4] |= value << (8 * (k % 4));
      }
    }
    for (uint32_t k = node.child_count; k < width; ++k)  // empty: lo 255, hi 0 (and meta 0)
      for (uint32_t coordinate = 0; coordinate < 3; ++coordinate) words[coordinate * per + k / 4] |= 255u << (8 * (k % 4));
    for (size_t w = 0; w < words.size(); w += 4)
      out.texels.push_back({words[w], w + 1 < words.size() ? words[w + 1] : 0u, w + 2 < words.size() ? words[w + 2] : 0u,
                            w + 3 < words.size() ? words[w + 3] : 0u});
  }
  return out;
}

}  // namespace

uint32_t texels_per_node(uint32_t width, BvhNodes nodes) {
  if (nodes == BvhNodes::Float) return width == 2 ? 4u : 1u + 6u * width / 4u;
  return 2u + (6u * quantised_uints(width) + 3u) / 4u;
}

BvhLayout encode_bvh(const BvhTree& tree, BvhNodes nodes, uint32_t node_base) {
  if (tree.width != 2 && tree.width != 4 && tree.width != 8) throw InternalError("bvh: width " + std::to_string(tree.width));
  if (tree.width == 2 && nodes == BvhNodes::Float) return encode_binary(tree, node_base);
  return encode_wide(tree, nodes, node_base);
}

Aabb decode_quantised_box(const BvhLayout& layout, uint32_t width, uint32_t n, uint32_t k) {
  const glm::uvec4* node = &layout.texels[static_cast<size_t>(n) * layout.texels_per_node];
  const glm::vec3 origin(glm::uintBitsToFloat(node[1].x), glm::uintBitsToFloat(node[1].y), glm::uintBitsToFloat(node[1].z));
  const uint32_t per = quantised_uints(width);
  Aabb box;
  for (uint32_t coordinate = 0; coordinate < 6; ++coordinate) {
    const uint32_t word = coordinate * per + k / 4;
    const uint32_t q = node[2 + word / 4][word % 4] >> (8 * (k % 4)) & 0xFFu;
    const int a = static_cast<int>(coordinate % 3);
    const float scale = std::ldexp(1.0f, static_cast<int>(node[1].w >> (8 * a) & 0xFFu) - 127);
    (coordinate < 3 ? box.min : box.max)[a] = dequantise(origin[a], q, scale);
  }
  return box;
}

}  // namespace sdfbench
