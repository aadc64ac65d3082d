#pragma once
// Structure views like the thesis' figures 6.6-6.7: the scene hash's cells, or the octree
// levels of one hash cell, painted over a rendered frame at its primary hit points.
#include <optional>

#include <glm/glm.hpp>

#include "renderers/renderer.h"
#include "renderers/sdf/scene_hash.h"

namespace sdfbench {

enum class StructureView { Hash, Octree };

// The default cell to show: among the cells holding hit points of the frame, the one whose
// octree is deepest, then the one covering the most pixels.
glm::uvec3 default_view_cell(const FrameImages& frame, const Scene& scene, const FrameRequest& request,
                             const sdf::SceneHash& hash);

// `frame` must carry its AOVs (depth, normal) and come from `request` on `scene`.
// Hash: each cell tinted with its own colour, cell boundaries drawn as lines. Octree: inside
// `cell` the leaves are tinted by depth (legend: depth 0 blue ... deepest red) with their
// boundaries drawn; the rest of the image is dimmed. Throws Error for a cell outside the hash.
FrameImages overlay_structure(const FrameImages& frame, const Scene& scene, const FrameRequest& request,
                              const sdf::SceneHash& hash, StructureView view, glm::uvec3 cell);

}  // namespace sdfbench
