#pragma once
// A BVH as the builder makes it, before any GPU layout: up to `width` children a node, each an
// inner node or a leaf of consecutive references. Every layout (bvh_layouts.h), the tree-quality
// figures (bvh_quality.h) and the tests' invariants read this one form.
#include <array>
#include <cstdint>
#include <vector>

#include "scenes/aabb.h"

namespace sdfbench {

inline constexpr uint32_t kMaxBvhWidth = 8;

struct BvhChild {
  Aabb box;
  uint32_t index = 0;  // an inner node's index, or a leaf's first reference
  uint32_t count = 0;  // 0: an inner node; else the leaf's references
  bool leaf() const { return count > 0; }
};

struct BvhTreeNode {
  std::array<BvhChild, kMaxBvhWidth> children;
  uint32_t child_count = 0;
};

struct BvhTree {
  uint32_t width = 2;
  std::vector<BvhTreeNode> nodes;    // nodes[0]: the root, an inner node (also for 0 or 1 primitives)
  std::vector<uint32_t> references;  // leaf contents, leaf after leaf: primitive ids (spatial splits repeat some)
  Aabb bounds;                       // the root's box
  uint32_t depth = 0;                // inner nodes on the longest root-to-leaf path
};

// Calls f(child) for every child slot of the subtree below node `root` (a node's slots before
// its inner children's).
template <class F>
void for_each_slot_below(const BvhTree& tree, uint32_t root, F f) {
  std::vector<uint32_t> stack{root};
  while (!stack.empty()) {
    const BvhTreeNode& n = tree.nodes[stack.back()];
    stack.pop_back();
    for (uint32_t k = 0; k < n.child_count; ++k) {
      const BvhChild& c = n.children[k];
      if (!c.leaf()) stack.push_back(c.index);
      f(c);
    }
  }
}

}  // namespace sdfbench
