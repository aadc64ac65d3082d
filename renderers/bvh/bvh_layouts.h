#pragma once
// The GPU layouts of a BvhTree (bvh.comp decodes them; every texel a uvec4, floats as their bits):
// - binary: the layout of Aila & Laine 2009, "Understanding the efficiency of ray traversal on
//   GPUs": a node holds both children's boxes (4 texels), so one fetch tests both children.
// - wide float: 4 or 8 children a node, their boxes as floats, one coordinate of 4 children a
//   texel (so the kernel slab-tests 4 children in one vec4 step): 1 + 6 * width / 4 texels.
// - wide quantised: the child boxes as 8-bit offsets on a grid of power-of-two steps from the
//   node's corner, in the style of the compressed wide BVH (Ylitie, Karras & Laine 2017,
//   "Efficient incoherent ray traversal on GPUs through compressed wide BVHs"): 2 + 6 * width / 16
//   texels (5 for 8 children against the float layout's 13). Decoded boxes contain the float ones.
// Both wide layouts keep a node's inner children consecutive and its leaves' references
// consecutive, so one texel names them all: (first inner child, first reference, 8 meta bytes).
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "renderers/bvh/bvh_tree.h"

namespace sdfbench {

enum class BvhNodes { Float, Quantised };

// The encoded tree: node n's texels start at node_texel[n] (layout nodes are numbered
// n = 0, 1, ... in the layout's order, which may differ from the tree's).
struct BvhLayout {
  std::vector<glm::uvec4> texels;
  uint32_t texels_per_node = 0;
  std::vector<uint32_t> references;   // the leaves' contents in the layout's order
  std::vector<uint32_t> node_of_tree;  // the layout node of each tree node
  uint32_t node_count() const { return texels_per_node ? static_cast<uint32_t>(texels.size() / texels_per_node) : 0; }
};

// A meta byte of the wide layouts: 0 an empty slot; kind 7 an inner child (the low 5 bits: its
// rank among the node's inner children); kind 1..6 a leaf of that many references (the low 5
// bits: its first one's offset from the node's first reference).
inline constexpr uint32_t kMetaInner = 7;
inline constexpr uint32_t kMaxWideLeaf = 6;

// `node_base`: the layout index of the tree's root in the table it joins (child indices are
// absolute). width 2 with Float: the Aila-Laine layout; otherwise the wide layouts.
BvhLayout encode_bvh(const BvhTree& tree, BvhNodes nodes, uint32_t node_base);
uint32_t texels_per_node(uint32_t width, BvhNodes nodes);

// The quantised layout's box of child `k` of layout node `n` as the kernel decodes it (for tests).
Aabb decode_quantised_box(const BvhLayout& layout, uint32_t width, uint32_t n, uint32_t k);

}  // namespace sdfbench
