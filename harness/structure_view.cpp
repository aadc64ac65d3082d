#include "harness/structure_view.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "renderers/frame_params.h"
#include "scenes/error.h"

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

}  // namespace

glm::uvec3 most_refined_cell(const sdf::SceneHash& hash) {
  size_t best = 0, best_nodes = 0;
  for (size_t c = 0; c < hash.cell_count(); ++c) {
    // A cell's tree occupies the nodes from its root up to the next cell's root.
    const size_t end = c + 1 < hash.cell_count() ? hash.cell_root[c + 1] : hash.nodes.size();
    const size_t nodes = end > hash.cell_root[c] ? end - hash.cell_root[c] : 1;
    if (nodes > best_nodes) best_nodes = nodes, best = c;
  }
  const uint32_t x = static_cast<uint32_t>(best % hash.dims.x), y = static_cast<uint32_t>((best / hash.dims.x) % hash.dims.y);
  return {x, y, static_cast<uint32_t>(best / (static_cast<size_t>(hash.dims.x) * hash.dims.y))};
}

FrameImages overlay_structure(const FrameImages& frame, const Scene& scene, const FrameRequest& request,
                              const sdf::SceneHash& hash, StructureView view, std::optional<glm::uvec3> cell) {
  const glm::uvec3 shown = cell.value_or(most_refined_cell(hash));
  if (glm::any(glm::greaterThanEqual(shown, hash.dims)))
    throw Error("--view-cell " + std::to_string(shown.x) + "," + std::to_string(shown.y) + "," + std::to_string(shown.z) +
                ": outside the hash's " + std::to_string(hash.dims.x) + "x" + std::to_string(hash.dims.y) + "x" +
                std::to_string(hash.dims.z) + " cells");
  const shading::FrameParams f = make_shading_inputs(scene, request).frame;
  const glm::vec3 origin(f.camera_origin), forward(f.camera_forward), right(f.camera_right), up(f.camera_up);
  const float pixel_angle = 2.0f * glm::length(up) / static_cast<float>(frame.height);  // footprint per unit distance
  const glm::vec3 hash_max = hash.origin + glm::vec3(hash.dims) * hash.cell_size;
  const size_t shown_index = shown.x + static_cast<size_t>(hash.dims.x) * (shown.y + static_cast<size_t>(hash.dims.y) * shown.z);
  const glm::vec3 shown_lo = hash.origin + glm::vec3(shown) * hash.cell_size;

  FrameImages out = frame;
  for (uint32_t y = 0; y < frame.height; ++y)
    for (uint32_t x = 0; x < frame.width; ++x) {
      const size_t i = static_cast<size_t>(y) * frame.width + x;
      glm::vec3 colour(frame.color[i]);
      const float t = frame.depth[i];
      if (view == StructureView::Octree) colour *= 0.35f;  // dim everything but the shown cell
      if (t > 0.0f) {
        const float sx = (static_cast<float>(x) + 0.5f) / static_cast<float>(frame.width) * 2.0f - 1.0f;
        const float sy = 1.0f - (static_cast<float>(y) + 0.5f) / static_cast<float>(frame.height) * 2.0f;
        const glm::vec3 p = origin + t * glm::normalize(forward + sx * right + sy * up);
        const float line = 1.2f * pixel_angle * t;
        const glm::vec3 n = frame.normal[i];
        if (glm::all(glm::greaterThanEqual(p, hash.origin)) && glm::all(glm::lessThan(p, hash_max))) {
          const glm::uvec3 c = glm::min(glm::uvec3((p - hash.origin) / hash.cell_size), hash.dims - 1u);
          const glm::vec3 lo = hash.origin + glm::vec3(c) * hash.cell_size;
          if (view == StructureView::Hash) {
            const size_t index = c.x + static_cast<size_t>(hash.dims.x) * (c.y + static_cast<size_t>(hash.dims.y) * c.z);
            colour = glm::mix(colour, cell_colour(index), 0.45f);
            if (distance_to_edges(p, lo, lo + hash.cell_size, n) < line) colour = glm::vec3(0.05f);
          } else if (c == shown) {
            // Descend to the leaf holding p (thesis Algorithm 5.7).
            const sdf::OctreeNode* node = &hash.nodes[hash.cell_root[shown_index]];
            glm::vec3 node_lo = shown_lo;
            float size = hash.cell_size;
            while (node->first_child >= 0) {
              size *= 0.5f;
              const glm::bvec3 upper = glm::greaterThanEqual(p, node_lo + size);
              const int octant = (upper.x ? 1 : 0) | (upper.y ? 2 : 0) | (upper.z ? 4 : 0);
              node_lo += glm::vec3(upper) * size;
              node = &hash.nodes[static_cast<size_t>(node->first_child) + octant];
            }
            colour = glm::mix(glm::vec3(frame.color[i]), depth_colour(node->depth, hash.params.octree_depth), 0.55f);
            if (distance_to_edges(p, node_lo, node_lo + size, n) < line) colour = glm::vec3(0.05f);
          }
        }
      }
      out.color[i] = glm::vec4(colour, frame.color[i].w);
    }
  return out;
}

}  // namespace sdfbench
