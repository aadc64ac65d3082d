#include "renderers/bvh/bvh_quality.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <random>
#include <utility>

namespace sdfbench {
namespace {

constexpr double kTraversalCost = 1.0, kIntersectionCost = 1.0;

double area(const Aabb& box) {
  if (box.empty()) return 0.0;
  const glm::dvec3 e = glm::dvec3(box.extent());
  return 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
}

bool inside(const Aabb& box, const glm::vec3& p) {
  return glm::all(glm::greaterThanEqual(p, box.min)) && glm::all(glm::lessThanEqual(p, box.max));
}

// A tree's subtrees as reference ranges (depth-first order: each is one range), and where each
// primitive is referenced, to ask "is primitive t in node n's subtree?".
class SubtreeIndex {
 public:
  SubtreeIndex(const BvhTree& tree, size_t primitives) : range_(tree.nodes.size()) {
    for (size_t n = tree.nodes.size(); n-- > 0;) {  // children follow their parent
      uint32_t lo = UINT32_MAX, hi = 0;
      const BvhTreeNode& node = tree.nodes[n];
      for (uint32_t k = 0; k < node.child_count; ++k) {
        const BvhChild& c = node.children[k];
        const auto r = c.leaf() ? std::pair{c.index, c.index + c.count} : range_[c.index];
        lo = std::min(lo, r.first);
        hi = std::max(hi, r.second);
      }
      range_[n] = lo < hi ? std::pair{lo, hi} : std::pair{0u, 0u};
    }
    first_.assign(primitives + 1, 0);
    for (uint32_t r : tree.references) ++first_[r + 1];
    for (size_t i = 1; i < first_.size(); ++i) first_[i] += first_[i - 1];
    positions_.resize(tree.references.size());
    std::vector<uint32_t> next(first_.begin(), first_.end() - 1);
    for (uint32_t p = 0; p < tree.references.size(); ++p) positions_[next[tree.references[p]]++] = p;
  }
  bool in_range(uint32_t primitive, uint32_t lo, uint32_t hi) const {
    for (uint32_t i = first_[primitive]; i < first_[primitive + 1]; ++i)
      if (positions_[i] >= lo && positions_[i] < hi) return true;
    return false;
  }
  bool in_subtree(uint32_t primitive, uint32_t node) const { return in_range(primitive, range_[node].first, range_[node].second); }

 private:
  std::vector<std::pair<uint32_t, uint32_t>> range_;
  std::vector<uint32_t> first_, positions_;
};

// A point of the scene's surface: a world triangle (instance, triangle; flat: instance 0 and
// the flat mesh's triangle).
struct SurfacePoint {
  uint32_t instance = 0, triangle = 0;
};

// The structure with its subtree indices: which node slots contain a surface point's triangle.
class Structure {
 public:
  Structure(const BvhScene& bvh, const Scene& scene) : bvh_(bvh), scene_(scene) {
    if (flat()) {
      top_index_.emplace_back(bvh.top, bvh.flat_mesh().triangles.size());
      return;
    }
    for (size_t m = 0; m < bvh.meshes.size(); ++m) mesh_index_.emplace_back(bvh.meshes[m], scene.meshes[m].triangles.size());
    top_index_.emplace_back(bvh.top, bvh.entries.size());
    entries_of_instance_.resize(scene.instances.size());
    for (uint32_t e = 0; e < bvh.entries.size(); ++e) entries_of_instance_[bvh.entries[e].instance].push_back(e);
  }
  bool flat() const { return bvh_.top_kind == BvhTop::Flat; }
  const BvhTree& mesh_tree(uint32_t instance) const { return bvh_.meshes[scene_.instances[instance].mesh]; }

  // Is the point's triangle under the mesh node `node` of `instance`'s tree (or, flat, under the top's)?
  bool mesh_contains(uint32_t instance, uint32_t node, const SurfacePoint& s) const {
    if (flat()) return top_index_[0].in_subtree(s.triangle, node);
    return instance == s.instance && mesh_index_[scene_.instances[instance].mesh].in_subtree(s.triangle, node);
  }
  bool mesh_leaf_contains(uint32_t instance, const BvhChild& leaf, const SurfacePoint& s) const {
    if (flat()) return top_index_[0].in_range(s.triangle, leaf.index, leaf.index + leaf.count);
    return instance == s.instance &&
           mesh_index_[scene_.instances[instance].mesh].in_range(s.triangle, leaf.index, leaf.index + leaf.count);
  }
  // The top level's entries that hold the point's triangle.
  std::vector<uint32_t> entries_holding(const SurfacePoint& s) const {
    std::vector<uint32_t> out;
    for (uint32_t e : entries_of_instance_[s.instance])
      if (mesh_contains(s.instance, bvh_.entries[e].node, s)) out.push_back(e);
    return out;
  }
  bool top_contains(uint32_t lo, uint32_t hi, const std::vector<uint32_t>& holding) const {
    return std::any_of(holding.begin(), holding.end(), [&](uint32_t e) { return top_index_[0].in_range(e, lo, hi); });
  }
  bool top_subtree_contains(uint32_t node, const std::vector<uint32_t>& holding) const {
    return std::any_of(holding.begin(), holding.end(), [&](uint32_t e) { return top_index_[0].in_subtree(e, node); });
  }

  const BvhScene& bvh_;
  const Scene& scene_;

 private:
  std::vector<SubtreeIndex> mesh_index_, top_index_;
  std::vector<std::vector<uint32_t>> entries_of_instance_;
};

// Per node of a tree: the SAH cost of its children (visits of inner children and their subtrees,
// leaves' triangle tests), in the tree's own area units.
std::vector<double> children_costs(const BvhTree& tree) {
  std::vector<double> cost(tree.nodes.size(), 0.0);
  for (size_t n = tree.nodes.size(); n-- > 0;)
    for (uint32_t k = 0; k < tree.nodes[n].child_count; ++k) {
      const BvhChild& c = tree.nodes[n].children[k];
      cost[n] += c.leaf() ? kIntersectionCost * c.count * area(c.box) : kTraversalCost * area(c.box) + cost[c.index];
    }
  return cost;
}

double scale_squared(const Scene& scene, uint32_t instance) {
  const double s = scene.instances[instance].transform.scale;
  return s * s;
}

// Visits every node slot (a child box) whose box contains p: inner slots and top-level entries
// cost C_t, leaves C_i per triangle, each counted when the point's triangle is not under it.
double point_overlap_cost(const Structure& st, const glm::vec3& p, const SurfacePoint& s) {
  double cost = 0;
  // A mesh subtree below `node` of `instance`, the point in its frame.
  std::function<void(uint32_t, uint32_t, const glm::vec3&)> mesh = [&](uint32_t instance, uint32_t node, const glm::vec3& q) {
    const BvhTree& tree = st.flat() ? st.bvh_.top : st.mesh_tree(instance);
    const BvhTreeNode& n = tree.nodes[node];
    for (uint32_t k = 0; k < n.child_count; ++k) {
      const BvhChild& c = n.children[k];
      if (!inside(c.box, q)) continue;
      if (c.leaf()) {
        if (!st.mesh_leaf_contains(instance, c, s)) cost += kIntersectionCost * c.count;
        continue;
      }
      if (!st.mesh_contains(instance, c.index, s)) cost += kTraversalCost;
      mesh(instance, c.index, q);
    }
  };
  if (st.flat()) {
    mesh(0, 0, p);
    return cost;
  }
  const std::vector<uint32_t> holding = st.entries_holding(s);
  std::function<void(uint32_t)> top = [&](uint32_t node) {
    const BvhTreeNode& n = st.bvh_.top.nodes[node];
    for (uint32_t k = 0; k < n.child_count; ++k) {
      const BvhChild& c = n.children[k];
      if (!inside(c.box, p)) continue;
      if (!c.leaf()) {
        if (!st.top_subtree_contains(c.index, holding)) cost += kTraversalCost;
        top(c.index);
        continue;
      }
      for (uint32_t r = c.index; r < c.index + c.count; ++r) {
        const uint32_t e = st.bvh_.top.references[r];
        const BvhEntry& entry = st.bvh_.entries[e];
        if (std::find(holding.begin(), holding.end(), e) == holding.end()) cost += kTraversalCost;
        const glm::mat4 to_object = st.scene_.instances[entry.instance].transform.world_to_object();
        mesh(entry.instance, entry.node, glm::vec3(to_object * glm::vec4(p, 1.0f)));
      }
    }
  };
  top(0);
  return cost;
}

// The world triangle of a surface point.
void world_triangle(const Structure& st, const SurfacePoint& s, glm::vec3 v[3]) {
  if (st.flat()) {
    const glm::uvec3 t = st.bvh_.flat_mesh().triangles[s.triangle];
    for (int k = 0; k < 3; ++k) v[k] = st.bvh_.flat_mesh().positions[t[k]];
    return;
  }
  const Instance& instance = st.scene_.instances[s.instance];
  const Mesh& mesh = st.scene_.meshes[instance.mesh];
  const glm::mat4 m = instance.transform.object_to_world();
  const glm::uvec3 t = mesh.triangles[s.triangle];
  for (int k = 0; k < 3; ++k) v[k] = glm::vec3(m * glm::vec4(mesh.positions[t[k]], 1.0f));
}

double triangle_area(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  return 0.5 * glm::length(glm::cross(glm::dvec3(b - a), glm::dvec3(c - a)));
}

// Every world triangle, for sampling and the exact sum.
std::vector<SurfacePoint> all_triangles(const Structure& st) {
  std::vector<SurfacePoint> out;
  if (st.flat()) {
    for (uint32_t t = 0; t < st.bvh_.flat_mesh().triangles.size(); ++t) out.push_back({0, t});
    return out;
  }
  for (uint32_t i = 0; i < st.scene_.instances.size(); ++i)
    for (uint32_t t = 0; t < st.scene_.meshes[st.scene_.instances[i].mesh].triangles.size(); ++t) out.push_back({i, t});
  return out;
}

// The area of a triangle's part inside a box (Sutherland-Hodgman against the 6 planes).
double clipped_area(const glm::vec3 v[3], const Aabb& box) {
  std::vector<glm::dvec3> poly = {v[0], v[1], v[2]};
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const double plane = side == 0 ? box.min[axis] : box.max[axis];
      const auto in = [&](const glm::dvec3& p) { return side == 0 ? p[axis] >= plane : p[axis] <= plane; };
      std::vector<glm::dvec3> next;
      for (size_t i = 0; i < poly.size(); ++i) {
        const glm::dvec3& a = poly[i];
        const glm::dvec3& b = poly[(i + 1) % poly.size()];
        if (in(a)) next.push_back(a);
        if (in(a) != in(b)) next.push_back(a + (plane - a[axis]) / (b[axis] - a[axis]) * (b - a));
      }
      poly = std::move(next);
      if (poly.size() < 3) return 0.0;
    }
  glm::dvec3 sum(0.0);
  for (size_t i = 1; i + 1 < poly.size(); ++i) sum += glm::cross(poly[i] - poly[0], poly[i + 1] - poly[0]);
  return 0.5 * glm::length(sum);
}

}  // namespace

double bvh_sah(const BvhScene& bvh, const Scene& scene) {
  const double root = area(bvh.top.bounds);
  if (root <= 0) return 0;
  const std::vector<double> top = children_costs(bvh.top);
  if (bvh.top_kind == BvhTop::Flat) return (kTraversalCost * root + top[0]) / root;
  std::vector<std::vector<double>> meshes;
  for (const BvhTree& tree : bvh.meshes) meshes.push_back(children_costs(tree));
  // The top level's inner visits, then each entry: its node's visit at its top-level box, and its
  // subtree at the instance's scale.
  double cost = kTraversalCost * root;
  for (const BvhTreeNode& node : bvh.top.nodes)
    for (uint32_t k = 0; k < node.child_count; ++k) {
      const BvhChild& c = node.children[k];
      if (!c.leaf()) {
        cost += kTraversalCost * area(c.box);
        continue;
      }
      for (uint32_t r = c.index; r < c.index + c.count; ++r) {
        const BvhEntry& e = bvh.entries[bvh.top.references[r]];
        cost += kTraversalCost * area(c.box) +
                scale_squared(scene, e.instance) * meshes[scene.instances[e.instance].mesh][e.node];
      }
    }
  return cost / root;
}

double bvh_epo(const BvhScene& bvh, const Scene& scene, uint32_t samples, uint64_t seed) {
  const Structure st(bvh, scene);
  // Triangles by world area: an instance by its mesh's area times its scale squared, then a
  // triangle of its mesh by area.
  std::vector<double> instance_area, mesh_area(scene.meshes.size(), 0.0);
  std::vector<std::vector<double>> triangle_cdf(st.flat() ? 1 : scene.meshes.size());
  const auto cdf_of = [](const Mesh& mesh, std::vector<double>& cdf) {
    double sum = 0;
    for (const glm::uvec3& t : mesh.triangles)
      cdf.push_back(sum += triangle_area(mesh.positions[t.x], mesh.positions[t.y], mesh.positions[t.z]));
    return sum;
  };
  if (st.flat()) {
    if (cdf_of(bvh.flat_mesh(), triangle_cdf[0]) <= 0) return 0;
  } else {
    for (size_t m = 0; m < scene.meshes.size(); ++m) mesh_area[m] = cdf_of(scene.meshes[m], triangle_cdf[m]);
    double sum = 0;
    for (uint32_t i = 0; i < scene.instances.size(); ++i)
      instance_area.push_back(sum += mesh_area[scene.instances[i].mesh] * scale_squared(scene, i));
    if (sum <= 0) return 0;
  }
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const auto pick = [&](const std::vector<double>& cdf) {
    const double x = u(rng) * cdf.back();
    return static_cast<uint32_t>(std::min<size_t>(std::upper_bound(cdf.begin(), cdf.end(), x) - cdf.begin(), cdf.size() - 1));
  };
  double total = 0;
  for (uint32_t i = 0; i < samples; ++i) {
    SurfacePoint s;
    s.instance = st.flat() ? 0 : pick(instance_area);
    s.triangle = pick(triangle_cdf[st.flat() ? 0 : scene.instances[s.instance].mesh]);
    glm::vec3 v[3];
    world_triangle(st, s, v);
    const double r1 = std::sqrt(u(rng)), r2 = u(rng);  // uniform on the triangle
    const glm::vec3 p = glm::vec3((1 - r1) * glm::dvec3(v[0]) + r1 * (1 - r2) * glm::dvec3(v[1]) + r1 * r2 * glm::dvec3(v[2]));
    total += point_overlap_cost(st, p, s);
  }
  return samples ? total / samples : 0.0;
}

double bvh_epo_exact(const BvhScene& bvh, const Scene& scene) {
  const Structure st(bvh, scene);
  const std::vector<SurfacePoint> triangles = all_triangles(st);
  std::vector<std::array<glm::vec3, 3>> world(triangles.size());
  double total_area = 0;
  for (size_t i = 0; i < triangles.size(); ++i) {
    world_triangle(st, triangles[i], world[i].data());
    total_area += triangle_area(world[i][0], world[i][1], world[i][2]);
  }
  if (total_area <= 0) return 0;
  double sum = 0;
  // A mesh slot's box is in its instance's frame: the triangles are taken there, and their areas
  // back to world units by the scale squared.
  const auto mesh_subtree = [&](uint32_t instance, uint32_t root) {
    const BvhTree& tree = st.flat() ? bvh.top : st.mesh_tree(instance);
    const glm::mat4 to_object = st.flat() ? glm::mat4(1.0f) : scene.instances[instance].transform.world_to_object();
    const double s2 = st.flat() ? 1.0 : scale_squared(scene, instance);
    for_each_slot_below(tree, root, [&](const BvhChild& c) {
      for (size_t t = 0; t < triangles.size(); ++t) {
        const bool holds = c.leaf() ? st.mesh_leaf_contains(instance, c, triangles[t]) : st.mesh_contains(instance, c.index, triangles[t]);
        if (holds) continue;
        glm::vec3 v[3];
        for (int j = 0; j < 3; ++j) v[j] = glm::vec3(to_object * glm::vec4(world[t][j], 1.0f));
        sum += (c.leaf() ? kIntersectionCost * c.count : kTraversalCost) * s2 * clipped_area(v, c.box);
      }
    });
  };
  if (st.flat()) {
    mesh_subtree(0, 0);
    return sum / total_area;
  }
  for (const BvhTreeNode& n : bvh.top.nodes)
    for (uint32_t k = 0; k < n.child_count; ++k) {
      const BvhChild& c = n.children[k];
      for (size_t t = 0; t < triangles.size(); ++t) {
        const std::vector<uint32_t> holding = st.entries_holding(triangles[t]);
        const bool holds = c.leaf() ? st.top_contains(c.index, c.index + c.count, holding) : st.top_subtree_contains(c.index, holding);
        if (!holds) sum += kTraversalCost * clipped_area(world[t].data(), c.box) * (c.leaf() ? c.count : 1);
      }
      if (c.leaf())
        for (uint32_t r = c.index; r < c.index + c.count; ++r) {
          const BvhEntry& e = bvh.entries[bvh.top.references[r]];
          mesh_subtree(e.instance, e.node);
        }
    }
  return sum / total_area;
}

BvhQuality bvh_quality(const BvhScene& bvh, const Scene& scene) {
  BvhQuality q;
  q.sah = bvh_sah(bvh, scene);
  q.epo = bvh_epo(bvh, scene);
  q.nodes = bvh.top.nodes.size();
  for (const BvhTree& tree : bvh.meshes) q.nodes += tree.nodes.size();
  q.entries = bvh.entries.size();
  return q;
}

}  // namespace sdfbench
