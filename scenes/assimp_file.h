#pragma once
// One PLY, OFF or glTF file read by assimp once sdfbench's own checks pass (mesh_file_check.h):
// the shared first half of mesh_file.h (a file as one mesh) and gltf_scene.h (a glTF file as a
// scene). Only these two include it (it brings assimp's headers).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <assimp/Importer.hpp>
#include <assimp/scene.h>

#include "scenes/mesh.h"

namespace sdfbench {

inline constexpr uint64_t kMaxMeshFileBytes = 512ull << 20;  // as an OBJ
inline constexpr uint32_t kMaxNodeDepth = 256;

struct AssimpFile {
  std::unique_ptr<Assimp::Importer> importer;  // owns the scene
  const aiScene* scene = nullptr;              // with a root node
};

// `format`: "ply", "off", "gltf" or "glb"; `where` prefixes every error; external files (a
// .gltf's buffers) are read from `folder` only (none without one). Throws Error.
AssimpFile import_checked(std::span<const std::byte> bytes, const std::string& format, const std::string& where,
                          std::optional<std::filesystem::path> folder);

// The triangles of `mesh` (polygons as fans, points and lines skipped, every index checked),
// transformed by `m`, appended to `out`, within kMaxMeshFileVertices / kMaxMeshFileTriangles.
// With `uv`: the first texture coordinate set per vertex appended too (zeros where the mesh has
// none), each finite and within kMaxTextureCoordinate.
void append_triangles(const aiMesh& mesh, const aiMatrix4x4& m, Mesh& out, const std::string& where,
                      std::vector<glm::vec2>* uv = nullptr);

// The largest texture coordinate accepted: beyond it a float uv no longer resolves a texel of a
// 16384-texel image.
inline constexpr float kMaxTextureCoordinate = 1e3f;

}  // namespace sdfbench
