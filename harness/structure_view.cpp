#include "harness/structure_view.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "renderers/frame_params.h"
#include "util/error.h"

namespace sdfbench {
namespace {

glm::vec3 hue(float h) {
  const glm::vec3 k = glm::abs(glm::fract(glm::vec3(h) + glm::vec3(0.0f, 2.0f / 3.0f, 1.0f / 3.0f)) * 6.0f - 3.0f) - 1.0f;
  return glm::clamp(k, 0.0f, 1.0f);
}

// Distinct neighbours: golden-ratio hue steps over the cell index.
glm::vec3 cell_colour(size_t index) { return hue(std::fmod(static_cast<float>(index) * 0.618034f, 1.0f)); }

glm::vec3 depth_colour(uint32_t depth, uint32_t max_depth) {
  return hue(0.66f * (1.0f - static_cast<float>(depth) / static_cast<float>(std::max(1u, max_depth))));
}

// World distance from p to the nearest face of `box` that crosses the surface (faces parallel
// to the surface would paint the whole surface, so they are skipped).
float distance_to_edges(const glm::vec3& p, const glm::vec3& lo, const glm::vec3& hi, const glm::vec3& normal) {
  float d = INFINITY;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(normal[a]) > 0.9f) continue;
    d = std::min({d, std::abs(p[a] - lo[a]), std::abs(hi[a] - p[a])});
  }
  return d;
}


// The world hit point of each pixel (camera ray x depth), or nullopt for the sky.
class HitPoints {
 public:
  HitPoints(const FrameImages& frame, const Scene& scene, const FrameRequest& request) : frame_(frame) {
    const shading::FrameParams f = make_shading_inputs(scene, request).frame;
    origin_ = glm::vec3(f.camera_origin), forward_ = glm::vec3(f.camera_forward), right_ = glm::vec3(f.camera_right);
    up_ = glm::vec3(f.camera_up);
  }
  std::optional<glm::vec3> at(uint32_t x, uint32_t y) const {
    const float t = frame_.depth[static_cast<size_t>(y) * frame_.width + x];
    if (t <= 0.0f) return std::nullopt;
    const float sx = (static_cast<float>(x) + 0.5f) / static_cast<float>(frame_.width) * 2.0f - 1.0f;
    const float sy = 1.0f - (static_cast<float>(y) + 0.5f) / static_cast<float>(frame_.height) * 2.0f;
    return origin_ + t * glm::normalize(forward_ + sx * right_ + sy * up_);
  }
  // World size of one pixel at ray distance t.
  float pixel_size(float t) const { return 2.0f * glm::length(up_) / static_cast<float>(frame_.height) * t; }

 private:
  const FrameImages& frame_;
  glm::vec3 origin_, forward_, right_, up_;
};

// The cell holding p; points a hair outside the box (a floor on its boundary plane) count as in.
std::optional<glm::uvec3> cell_of(const sdf::SceneHash& hash, const glm::vec3& p) {
  const glm::vec3 f = (p - hash.origin) / hash.cell_size;
  const float slack = 1e-3f;
  if (glm::any(glm::lessThan(f, glm::vec3(-slack))) || glm::any(glm::greaterThan(f, glm::vec3(hash.dims) + slack)))
    return std::nullopt;
  return glm::min(glm::uvec3(glm::max(f, glm::vec3(0.0f))), hash.dims - 1u);
}

size_t cell_index(const sdf::SceneHash& hash, const glm::uvec3& c) {
  return c.x + static_cast<size_t>(hash.dims.x) * (c.y + static_cast<size_t>(hash.dims.y) * c.z);
}

// Deepest node of a cell's tree: its nodes run from its root to the next tree's root (trees are
// appended in cell order).
uint32_t tree_depth(const sdf::SceneHash& hash, size_t cell) {
  const size_t end = cell + 1 < hash.cell_count() ? hash.cell_root[cell + 1] : hash.nodes.size();
  uint32_t depth = 0;
  for (size_t n = hash.cell_root[cell]; n < end; ++n) depth = std::max(depth, hash.nodes[n].depth);
  return depth;
}

}  // namespace

glm::uvec3 default_view_cell(const FrameImages& frame, const Scene& scene, const FrameRequest& request,
                             const sdf::SceneHash& hash) {
  const HitPoints hits(frame, scene, request);
  std::vector<size_t> pixels(hash.cell_count(), 0);
  for (uint32_t y = 0; y < frame.height; ++y)
    for (uint32_t x = 0; x < frame.width; ++x)
      if (const auto p = hits.at(x, y))
        if (const auto c = cell_of(hash, *p)) ++pixels[cell_index(hash, *c)];
  size_t best = 0;
  std::pair<uint32_t, size_t> best_score{0, 0};  // (tree depth, pixels): the deepest, then the largest on screen
  for (size_t c = 0; c < hash.cell_count(); ++c) {
    const std::pair<uint32_t, size_t> score{pixels[c] ? tree_depth(hash, c) : 0, pixels[c]};
    if (score > best_score) best_score = score, best = c;
  }
  const uint32_t x = static_cast<uint32_t>(best % hash.dims.x), y = static_cast<uint32_t>((best / hash.dims.x) % hash.dims.y);
  return {x, y, static_cast<uint32_t>(best / (static_cast<size_t>(hash.dims.x) * hash.dims.y))};
}

FrameImages overlay_structure(const FrameImages& frame, const Scene& scene, const FrameRequest& request,
                              const sdf::SceneHash& hash, StructureView view, glm::uvec3 shown) {
  if (glm::any(glm::greaterThanEqual(shown, hash.dims)))
    throw Error("--view-cell " + std::to_string(shown.x) + "," + std::to_string(shown.y) + "," + std::to_string(shown.z) +
                ": outside the hash's " + std::to_string(hash.dims.x) + "x" + std::to_string(hash.dims.y) + "x" +
                std::to_string(hash.dims.z) + " cells");
  const HitPoints hits(frame, scene, request);
  const glm::vec3 shown_lo = hash.origin + glm::vec3(shown) * hash.cell_size;
  FrameImages out = frame;
  for (uint32_t y = 0; y < frame.height; ++y)
    for (uint32_t x = 0; x < frame.width; ++x) {
      const size_t i = static_cast<size_t>(y) * frame.width + x;
      const glm::vec3 shaded(frame.color[i]);
      glm::vec3 colour = view == StructureView::Octree ? 0.35f * shaded : shaded;  // octree: dim all but the cell
      const auto p = hits.at(x, y);
      const auto c = p ? cell_of(hash, *p) : std::nullopt;
      if (c) {
        const float line = 1.2f * hits.pixel_size(frame.depth[i]);
        const glm::vec3 n = frame.normal[i];
        const glm::vec3 lo = hash.origin + glm::vec3(*c) * hash.cell_size;
        if (view == StructureView::Hash) {
          colour = glm::mix(shaded, cell_colour(cell_index(hash, *c)), 0.45f);
          if (distance_to_edges(*p, lo, lo + hash.cell_size, n) < line) colour = glm::vec3(0.05f);
        } else if (*c == shown) {
          // Descend to the leaf holding p (thesis Algorithm 5.7).
          const sdf::OctreeNode* node = &hash.nodes[hash.cell_root[cell_index(hash, shown)]];
          glm::vec3 node_lo = shown_lo;
          float size = hash.cell_size;
          while (node->first_child >= 0) {
            size *= 0.5f;
            const glm::bvec3 upper = glm::greaterThanEqual(*p, node_lo + size);
            const int octant = (upper.x ? 1 : 0) | (upper.y ? 2 : 0) | (upper.z ? 4 : 0);
            node_lo += glm::vec3(upper) * size;
            node = &hash.nodes[static_cast<size_t>(node->first_child) + octant];
          }
          colour = glm::mix(shaded, depth_colour(node->depth, hash.params.octree_depth), 0.55f);
          // Leaf outlines only where a leaf spans a few pixels; smaller leaves show as colour alone.
          if (size > 4.0f * line && distance_to_edges(*p, node_lo, node_lo + size, n) < line) colour = glm::vec3(0.05f);
        }
      }
      out.color[i] = glm::vec4(colour, frame.color[i].w);
    }
  return out;
}

}  // namespace sdfbench
