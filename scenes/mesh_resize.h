#pragma once
// One shape at any size, for the mesh-size axis (`thesis:<mesh>@<triangles>:<count>`): the mesh
// welded by position, refined by Loop subdivision (OpenMesh) until it has at least the target
// triangle count, then simplified down to it (meshoptimizer's edge-collapse simplifier, no
// error limit). Single-threaded and without randomness, so the same input gives the same mesh.
#include <cstdint>

#include "scenes/mesh.h"

namespace sdfbench {

inline constexpr uint32_t kMinResizedTriangles = 100;
inline constexpr uint32_t kMaxResizedTriangles = 2'000'000;  // the subdivided mesh stays < 8 M triangles
// The result has target ± this fraction of triangles (the simplifier stops at a collapse that
// would go below the target; measured on the thesis meshes, 1k..1M: under 0.1 %).
inline constexpr double kResizeTolerance = 0.01;

// Throws Error (naming the mesh) for a target outside [kMinResizedTriangles,
// kMaxResizedTriangles], a mesh with more than 0.1 % of its triangles on non-manifold edges
// (fewer are left out, with a note on stderr: OpenMesh cannot hold them), or a result outside
// the tolerance. The result's name is "<name>@<target>"; normals and bounds are filled.
Mesh resize_mesh(const Mesh& mesh, uint32_t target_triangles);

}  // namespace sdfbench
