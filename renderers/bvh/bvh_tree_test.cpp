// The BVH's trees before any GPU work: every width's invariants (each primitive reachable, child
// boxes inside their parents', leaves around what they hold), quantised boxes that contain the
// float ones, re-braided entries that cover each instance once, the SAH cost of a tree worked
// by hand, the sampled EPO against the exact sum (every triangle clipped against every box),
// and the flat tree refused beyond --max-structure-mb.
#include <algorithm>
#include <map>
#include <set>

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "renderers/bvh/bvh_layouts.h"
#include "renderers/bvh/bvh_quality.h"
#include "renderers/bvh/bvh_scene.h"
#include "scenes/mesh.h"
#include "scenes/thesis_layout.h"
#include "tests/test_support.h"
#include "util/error.h"

namespace sdfbench {
namespace {

bool contains(const Aabb& outer, const Aabb& inner) {
  return glm::all(glm::lessThanEqual(outer.min, inner.min)) && glm::all(glm::greaterThanEqual(outer.max, inner.max));
}

class EmbreeDevice {
 public:
  EmbreeDevice() : device(rtcNewDevice("threads=2")) {}
  ~EmbreeDevice() { rtcReleaseDevice(device); }
  RTCDevice device;
};

// A panel of n x n quads at height y, for small scenes whose EPO can be summed exactly.
Mesh panel(uint32_t n) {
  Mesh mesh;
  mesh.name = "panel";
  for (uint32_t j = 0; j <= n; ++j)
    for (uint32_t i = 0; i <= n; ++i)
      mesh.positions.emplace_back(float(i) / n, 0.3f * std::sin(float(i + 2 * j)), float(j) / n);
  for (uint32_t j = 0; j < n; ++j)
    for (uint32_t i = 0; i < n; ++i) {
      const uint32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      mesh.triangles.emplace_back(a, c, b);
      mesh.triangles.emplace_back(b, c, d);
    }
  finish_mesh(mesh);
  return mesh;
}

// Three overlapping, rotated and scaled panels.
Scene overlapping_panels() {
  Scene scene;
  scene.meshes.push_back(panel(4));
  for (int i = 0; i < 3; ++i) {
    Instance instance;
    instance.transform.translation = glm::vec3(0.3f * i, 0.1f * i, 0.2f * i);
    instance.transform.rotation = glm::angleAxis(0.4f * i, glm::normalize(glm::vec3(1, 2, 0.5f)));
    instance.transform.scale = 1.0f + 0.25f * i;
    scene.instances.push_back(instance);
  }
  return scene;
}

TEST(BvhTree, EveryWidthKeepsItsInvariants) {
  EmbreeDevice embree;
  const Mesh mesh = load_obj(builtin_mesh_path("teapot"), "teapot");
  std::vector<Aabb> boxes(mesh.triangles.size());
  for (size_t i = 0; i < boxes.size(); ++i)
    for (int k = 0; k < 3; ++k) boxes[i].extend(mesh.positions[mesh.triangles[i][k]]);
  for (uint32_t width : {2u, 4u, 8u})
    for (bool splits : {false, true}) {
      BvhBuildParams params;
      params.width = width;
      const BvhTree tree = splits ? build_mesh_bvh(embree.device, mesh, params) : build_bvh(embree.device, boxes, params);
      SCOPED_TRACE("width " + std::to_string(width) + (splits ? ", spatial splits" : ""));
      const std::set<uint32_t> seen(tree.references.begin(), tree.references.end());
      EXPECT_EQ(seen.size(), boxes.size());
      if (!splits) {
        EXPECT_EQ(tree.references.size(), boxes.size()) << "without splits each triangle once";
      }
      EXPECT_GT(tree.depth, 3u);
      EXPECT_LE(tree.depth, 64u);
      // Walk from the root: every node reached once, children inside their parent's slot.
      std::vector<int> reached(tree.nodes.size(), 0);
      std::vector<std::pair<uint32_t, Aabb>> stack{{0, tree.bounds}};
      size_t referenced = 0;
      while (!stack.empty()) {
        const auto [n, parent] = stack.back();
        stack.pop_back();
        ++reached[n];
        const BvhTreeNode& node = tree.nodes[n];
        EXPECT_LE(node.child_count, width);
        EXPECT_GE(node.child_count, n == 0 ? 1u : 2u);
        for (uint32_t k = 0; k < node.child_count; ++k) {
          const BvhChild& c = node.children[k];
          EXPECT_TRUE(contains(parent, c.box)) << "node " << n << " child " << k;
          if (!c.leaf()) {
            stack.push_back({c.index, c.box});
            continue;
          }
          referenced += c.count;
          for (uint32_t r = c.index; !splits && r < c.index + c.count; ++r) EXPECT_TRUE(contains(c.box, boxes[tree.references[r]]));
        }
      }
      EXPECT_EQ(std::count(reached.begin(), reached.end(), 1), static_cast<long>(tree.nodes.size())) << "each node reached once";
      EXPECT_EQ(referenced, tree.references.size()) << "each reference in one leaf";

      // Quantised boxes contain the float ones; the layouts keep every leaf's references.
      for (BvhNodes nodes : {BvhNodes::Float, BvhNodes::Quantised}) {
        const BvhLayout layout = encode_bvh(tree, nodes, 0);
        EXPECT_EQ(layout.node_count(), tree.nodes.size());
        EXPECT_EQ(std::multiset<uint32_t>(layout.references.begin(), layout.references.end()),
                  std::multiset<uint32_t>(tree.references.begin(), tree.references.end()));
        if (nodes != BvhNodes::Quantised) continue;
        size_t grown = 0;
        for (size_t n = 0; n < tree.nodes.size(); ++n)
          for (uint32_t k = 0; k < tree.nodes[n].child_count; ++k) {
            const Aabb exact = tree.nodes[n].children[k].box;
            const Aabb coarse = decode_quantised_box(layout, width, layout.node_of_tree[n], k);
            EXPECT_TRUE(contains(coarse, exact)) << "node " << n << " child " << k;
            grown += glm::any(glm::notEqual(coarse.min, exact.min)) || glm::any(glm::notEqual(coarse.max, exact.max));
          }
        EXPECT_GT(grown, 0u) << "8-bit boxes should round most boxes outwards";
      }
    }
  // No primitives: a root without children.
  const BvhTree none = build_bvh(embree.device, {}, BvhBuildParams{});
  ASSERT_EQ(none.nodes.size(), 1u);
  EXPECT_EQ(none.nodes[0].child_count, 0u);
}

TEST(BvhTree, RebraidedEntriesCoverEveryInstanceOnce) {
  EmbreeDevice embree;
  const Scene scene = make_thesis_scene({"teapot", 20, 2});
  for (uint32_t width : {2u, 8u}) {
    const BvhScene bvh = build_bvh_scene(embree.device, scene, {width, BvhTop::Rebraided, 3.0});
    EXPECT_GT(bvh.entries.size(), scene.instances.size()) << "the largest instances were opened";
    EXPECT_LE(bvh.entries.size(), 3 * scene.instances.size());
    // Each instance's leaves are under exactly one of its entries.
    std::map<uint32_t, std::vector<uint32_t>> of_instance;
    for (const BvhEntry& e : bvh.entries) of_instance[e.instance].push_back(e.node);
    EXPECT_EQ(of_instance.size(), scene.instances.size());
    const BvhTree& tree = bvh.meshes[0];
    for (const auto& [instance, nodes] : of_instance) {
      std::vector<int> leaves(tree.references.size(), 0);
      for (uint32_t root : nodes)
        for_each_slot_below(tree, root, [&](const BvhChild& c) {
          for (uint32_t r = c.index; c.leaf() && r < c.index + c.count; ++r) ++leaves[r];
        });
      EXPECT_EQ(std::count(leaves.begin(), leaves.end(), 1), static_cast<long>(leaves.size())) << "instance " << instance;
    }
  }
}

// One node over two leaves: SAH = (C_t A(root) + C_i n0 A(leaf 0) + C_i n1 A(leaf 1)) / A(root),
// the areas worked out here by hand.
TEST(BvhQuality, SahOfATreeWorkedByHand) {
  BvhScene bvh;
  bvh.top_kind = BvhTop::Flat;
  bvh.top.width = 2;
  bvh.top.bounds.min = {0, 0, 0};
  bvh.top.bounds.max = {2, 1, 1};  // area 2 (2 + 1 + 2) = 10
  BvhTreeNode root;
  root.child_count = 2;
  root.children[0].box.min = {0, 0, 0};
  root.children[0].box.max = {1, 1, 1};  // area 6, 3 triangles
  root.children[0].count = 3;
  root.children[1].box.min = {1, 0, 0};
  root.children[1].box.max = {2, 1, 0.5f};  // area 2 (1 + 0.5 + 0.5) = 4, 1 triangle
  root.children[1].index = 3;
  root.children[1].count = 1;
  bvh.top.nodes.push_back(root);
  bvh.top.references = {0, 1, 2, 3};
  EXPECT_NEAR(bvh_sah(bvh, Scene{}), (10.0 + 3 * 6.0 + 1 * 4.0) / 10.0, 1e-9);
}

// The sampled EPO (the rows' figure) against the exact sum, on scenes small enough to clip every
// triangle against every box: instanced, re-braided and flat, each with real overlap.
TEST(BvhQuality, SampledEpoMatchesTheExactSum) {
  EmbreeDevice embree;
  const Scene scene = overlapping_panels();
  for (BvhTop top : {BvhTop::Instanced, BvhTop::Rebraided, BvhTop::Flat})
    for (uint32_t width : {2u, 4u}) {
      const BvhScene bvh = build_bvh_scene(embree.device, scene, {width, top, 4.0});
      const double exact = bvh_epo_exact(bvh, scene);
      const double sampled = bvh_epo(bvh, scene, 200000, 7);
      SCOPED_TRACE("top " + std::to_string(int(top)) + ", width " + std::to_string(width));
      EXPECT_GT(exact, 0.1) << "the panels overlap: some geometry lies in boxes not its own";
      EXPECT_NEAR(sampled, exact, 0.03 * exact + 0.01);
      EXPECT_GT(bvh_sah(bvh, scene), 1.0);
    }
}

TEST(BvhScene, FlatTreeBeyondTheCapIsRefused) {
  EmbreeDevice embree;
  const Scene scene = make_thesis_scene({"bunny", 50, 1});
  ASSERT_GT(flat_bvh_bytes(scene), uint64_t(1) << 20);
  try {
    build_bvh_scene(embree.device, scene, {4, BvhTop::Flat, 2.0, uint64_t(1) << 20});
    ADD_FAILURE() << "a flat tree over the cap was built";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--max-structure-mb 1 "), std::string::npos) << e.what();
  }
  const test::CommandResult r = test::run_sdfbench(
      "render --scene thesis:bunny:50 --backend bvh --bvh-top flat --max-structure-mb 1 --size 32x18");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("sdfbench: error: bvh: --bvh-top flat needs about"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("--max-structure-mb"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace sdfbench
