#pragma once
// Field-by-field equality of two mesh distance grids (determinism, cache round trips).
#include <gtest/gtest.h>

#include "renderers/sdf/mesh_distance_grid.h"

namespace sdfbench::test {

inline void expect_same_grid(const sdf::MeshDistanceGrid& a, const sdf::MeshDistanceGrid& b) {
  EXPECT_EQ(a.origin, b.origin);
  EXPECT_EQ(a.cell_size, b.cell_size);
  EXPECT_EQ(a.dims, b.dims);
  EXPECT_EQ(a.cell_begin, b.cell_begin);
  EXPECT_EQ(a.cell_triangles, b.cell_triangles);
  EXPECT_EQ(a.face_normals, b.face_normals);
  EXPECT_EQ(a.edge_normals, b.edge_normals);
  EXPECT_EQ(a.vertex_normals, b.vertex_normals);
  EXPECT_EQ(a.far_distance, b.far_distance);
  EXPECT_EQ(a.far_upper, b.far_upper);
}

}  // namespace sdfbench::test
