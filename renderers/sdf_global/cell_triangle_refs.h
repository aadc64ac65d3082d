#pragma once
// sdf-global's exact hits through triangle references (issue 37, --exact-lists triangles): the
// global field's stored bricks cut into reference cells (--list-split per voxel and axis), each
// with the set of (instance, triangle) pairs whose triangle crosses the cell grown by
// kRefSlackVoxels, built once with the field (as AMD's Brixelizer keeps (voxel, triangle)
// references). Near a surface the kernel walks the ray's cells and tests each cell's set once, in
// the instances' own frames (one transform per instance of the set): no instance list, no mesh-grid
// walk. Every crossing inside a cell is in its set, so the first cell along the ray whose set has a
// crossing within the cell holds the ray's hit. Sets are shared between cells that list the same
// pairs.
#include <cstdint>
#include <vector>

#include "renderers/sdf_bricks/brick_field.h"
#include "scenes/scene.h"

namespace sdfbench::sdf {

// A stored brick that no triangle crosses has no cell table.
inline constexpr uint32_t kNoCellTable = 0xffffffffu;
// A set word with this bit is an instance: the triangle words after it are that instance's.
inline constexpr uint32_t kInstanceWord = 0x80000000u;
// Cells are grown by this many voxels (and a rounding slack of the coordinates) before the
// triangles are tested against them: a window's test starts BRICK_BEHIND_VOXELS behind its point,
// and reaches a rounding slack past the cell's far face (brick_trace.glsl).
inline constexpr float kRefSlackVoxels = 0.02f;
inline constexpr uint32_t kMaxListSplit = 4;

struct CellTriangleRefs {
  uint32_t split = 1;            // reference cells per voxel and axis
  uint32_t cells_per_side = 0;   // per brick and axis: kBrickCells * split
  // Per stored brick: where its cell table (cells_per_side^3 words, x fastest) starts in `cells`,
  // or kNoCellTable.
  std::vector<uint32_t> brick_tables;
  std::vector<uint32_t> cells;  // per cell of a table: its set's offset in `sets` (0: the empty set)
  // Sets: a count n, then n words (instance words and global triangle indices: the meshes'
  // triangles concatenated in scene order, as the kernels' vertex tables hold them).
  std::vector<uint32_t> sets;
  uint64_t references = 0;  // (cell, instance, triangle) references, before sets were shared
  double build_ms = 0.0;

  size_t bytes() const { return (brick_tables.size() + cells.size() + sets.size()) * sizeof(uint32_t); }
};

// Built in parallel (TBB) for the stored bricks of `field` (world space, the scene's instances).
// Throws Error when the references would pass `max_bytes` (--max-structure-mb) or 32-bit indices,
// naming the flags that shrink them.
CellTriangleRefs build_cell_triangle_refs(const Scene& scene, const BrickField& field, uint32_t split, uint64_t max_bytes);

}  // namespace sdfbench::sdf
