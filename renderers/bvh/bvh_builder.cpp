#include "renderers/bvh/bvh_builder.h"

#include <algorithm>
#include <limits>
#include <string>

#include "util/error.h"


namespace sdfbench {
namespace {

// The builder's tree, in memory Embree's thread-local allocator owns (freed with the RTCBVH).
struct BuildNode {
  bool leaf;
};
struct InnerNode : BuildNode {
  unsigned child_count;
  BuildNode* children[kMaxBvhWidth];
  Aabb bounds[kMaxBvhWidth];
};
struct LeafNode : BuildNode {
  uint32_t count;
  uint32_t ids[1];  // `count` of them
};

struct BuildContext {
  const SplitPrimitive* split;
};

void* create_node(RTCThreadLocalAllocator allocator, unsigned, void*) {
  auto* node = static_cast<InnerNode*>(rtcThreadLocalAlloc(allocator, sizeof(InnerNode), 16));
  node->leaf = false;
  node->child_count = 0;
  return node;
}

void set_node_children(void* node, void** children, unsigned child_count, void*) {
  auto* inner = static_cast<InnerNode*>(node);
  inner->child_count = std::min(child_count, kMaxBvhWidth);
  for (unsigned i = 0; i < inner->child_count; ++i) inner->children[i] = static_cast<BuildNode*>(children[i]);
}

void set_node_bounds(void* node, const RTCBounds** bounds, unsigned child_count, void*) {
  auto* inner = static_cast<InnerNode*>(node);
  for (unsigned i = 0; i < child_count && i < kMaxBvhWidth; ++i) {
    inner->bounds[i].min = {bounds[i]->lower_x, bounds[i]->lower_y, bounds[i]->lower_z};
    inner->bounds[i].max = {bounds[i]->upper_x, bounds[i]->upper_y, bounds[i]->upper_z};
  }
}

void* create_leaf(RTCThreadLocalAllocator allocator, const RTCBuildPrimitive* primitives, size_t count, void*) {
  auto* leaf = static_cast<LeafNode*>(rtcThreadLocalAlloc(allocator, sizeof(LeafNode) + count * sizeof(uint32_t), 16));
  leaf->leaf = true;
  leaf->count = static_cast<uint32_t>(count);
  for (size_t i = 0; i < count; ++i) leaf->ids[i] = primitives[i].primID;
  return leaf;
}

void split_primitive(const RTCBuildPrimitive* primitive, unsigned dimension, float position, RTCBounds* left,
                     RTCBounds* right, void* user) {
  const auto* context = static_cast<const BuildContext*>(user);
  Aabb part;
  part.min = {primitive->lower_x, primitive->lower_y, primitive->lower_z};
  part.max = {primitive->upper_x, primitive->upper_y, primitive->upper_z};
  Aabb l, r;
  (*context->split)(primitive->primID, part, dimension, position, l, r);
  *left = {l.min.x, l.min.y, l.min.z, 0.0f, l.max.x, l.max.y, l.max.z, 0.0f};
  *right = {r.min.x, r.min.y, r.min.z, 0.0f, r.max.x, r.max.y, r.max.z, 0.0f};
}


// Depth-first: a node, then its children's subtrees in order (so every subtree is one range of
// nodes and one range of references).
class Flattener {
 public:
  explicit Flattener(BvhTree& out) : out_(out) {}

  // Appends `node` (and its subtree); returns its index.
  uint32_t inner(const InnerNode* node, uint32_t depth) {
    out_.depth = std::max(out_.depth, depth);
    const uint32_t index = static_cast<uint32_t>(out_.nodes.size());
    out_.nodes.emplace_back();
    BvhTreeNode flat;
    flat.child_count = node->child_count;
    for (unsigned i = 0; i < node->child_count; ++i) flat.children[i] = child(node->children[i], node->bounds[i], depth);
    out_.nodes[index] = flat;
    return index;
  }

 private:
  BvhChild child(const BuildNode* node, const Aabb& box, uint32_t depth) {
    BvhChild c;
    c.box = box;
    if (node->leaf) {
      const auto* leaf = static_cast<const LeafNode*>(node);
      c.index = static_cast<uint32_t>(out_.references.size());
      c.count = leaf->count;
      out_.references.insert(out_.references.end(), leaf->ids, leaf->ids + leaf->count);
    } else {
      c.index = inner(static_cast<const InnerNode*>(node), depth + 1);
      c.count = 0;
    }
    return c;
  }

  BvhTree& out_;
};

}  // namespace

void split_triangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const Aabb& part, unsigned dimension,
                    float position, Aabb& left, Aabb& right) {
  const glm::vec3 v[3] = {a, b, c};
  left = right = Aabb{};
  for (int i = 0; i < 3; ++i) {
    const glm::vec3& p = v[i];
    const glm::vec3& q = v[(i + 1) % 3];
    const float pd = p[dimension], qd = q[dimension];
    if (pd <= position) left.extend(p);
    if (pd >= position) right.extend(p);
    if ((pd < position && position < qd) || (qd < position && position < pd)) {
      const glm::vec3 crossing = p + (position - pd) / (qd - pd) * (q - p);
      left.extend(crossing);
      right.extend(crossing);
    }
  }
  // Only the part of the triangle the primitive stands for (an earlier split may have cut it).
  left.min = glm::max(left.min, part.min);
  left.max = glm::min(left.max, part.max);
  right.min = glm::max(right.min, part.min);
  right.max = glm::min(right.max, part.max);
  left.max[dimension] = std::min(left.max[dimension], position);
  right.min[dimension] = std::max(right.min[dimension], position);
}

BvhTree build_bvh(RTCDevice device, const std::vector<Aabb>& boxes, const BvhBuildParams& params,
                  const SplitPrimitive& split) {
  if (params.width < 2 || params.width > kMaxBvhWidth) throw InternalError("bvh: width " + std::to_string(params.width));
  BvhTree flat;
  flat.width = params.width;
  for (const Aabb& b : boxes) flat.bounds.extend(b);
  if (boxes.empty()) {
    Flattener f(flat);
    InnerNode none{};
    none.leaf = false;
    f.inner(&none, 1);
    return flat;
  }
  // Spatial splits need room for the references they add (Embree's tutorial: twice the count).
  const bool splits = static_cast<bool>(split) && params.quality == RTC_BUILD_QUALITY_HIGH;
  std::vector<RTCBuildPrimitive> primitives(splits ? 2 * boxes.size() : boxes.size());
  for (size_t i = 0; i < boxes.size(); ++i) {
    const Aabb& b = boxes[i];
    primitives[i] = {b.min.x, b.min.y, b.min.z, 0u, b.max.x, b.max.y, b.max.z, static_cast<uint32_t>(i)};
  }
  BuildContext context{&split};
  RTCBVH bvh = rtcNewBVH(device);
  if (!bvh) throw Error("Embree: rtcNewBVH failed (error " + std::to_string(rtcGetDeviceError(device)) + ")");
  RTCBuildArguments args = rtcDefaultBuildArguments();
  args.byteSize = sizeof(args);
  args.buildQuality = splits ? RTC_BUILD_QUALITY_HIGH : (params.quality == RTC_BUILD_QUALITY_LOW ? RTC_BUILD_QUALITY_LOW
                                                                                                   : RTC_BUILD_QUALITY_MEDIUM);
  args.maxBranchingFactor = params.width;
  args.maxDepth = params.max_depth;
  args.sahBlockSize = 1;
  args.minLeafSize = 1;
  args.maxLeafSize = params.max_leaf_size;
  args.traversalCost = params.traversal_cost;
  args.intersectionCost = params.intersection_cost;
  args.bvh = bvh;
  args.primitives = primitives.data();
  args.primitiveCount = boxes.size();
  args.primitiveArrayCapacity = primitives.size();
  args.createNode = create_node;
  args.setNodeChildren = set_node_children;
  args.setNodeBounds = set_node_bounds;
  args.createLeaf = create_leaf;
  args.splitPrimitive = splits ? split_primitive : nullptr;
  args.userPtr = &context;
  const auto* root = static_cast<const BuildNode*>(rtcBuildBVH(&args));
  if (!root) {
    rtcReleaseBVH(bvh);
    throw Error("Embree: rtcBuildBVH failed (error " + std::to_string(rtcGetDeviceError(device)) + ")");
  }
  Flattener f(flat);
  if (root->leaf) {  // a single leaf: under a root of its own
    InnerNode top{};
    top.leaf = false;
    top.child_count = 1;
    top.children[0] = const_cast<BuildNode*>(root);
    top.bounds[0] = flat.bounds;
    f.inner(&top, 1);
  } else {
    f.inner(static_cast<const InnerNode*>(root), 1);
  }
  rtcReleaseBVH(bvh);
  return flat;
}

BvhTree build_mesh_bvh(RTCDevice device, const Mesh& mesh, const BvhBuildParams& params) {
  std::vector<Aabb> boxes(mesh.triangles.size());
  for (size_t i = 0; i < boxes.size(); ++i)
    for (int k = 0; k < 3; ++k) boxes[i].extend(mesh.positions[mesh.triangles[i][k]]);
  const SplitPrimitive split = [&mesh](uint32_t id, const Aabb& part, unsigned dim, float pos, Aabb& l, Aabb& r) {
    const glm::uvec3& t = mesh.triangles[id];
    split_triangle(mesh.positions[t.x], mesh.positions[t.y], mesh.positions[t.z], part, dim, pos, l, r);
  };
  return build_bvh(device, boxes, params, split);
}

}  // namespace sdfbench
