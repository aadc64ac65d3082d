#pragma once
// What a PLY, OFF or glTF file claims, checked before a parser allocates for it (mesh_file.h):
// element and accessor counts against the limits and against the bytes that could hold them,
// glTF indices in range, buffers that lie inside the file's folder and node graphs without
// cycles. A hostile header costs a few kilobytes to refuse, never the gigabytes it declares.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace sdfbench {

// The most vertices and triangles one mesh file may hold (as OBJ: obj_loader.cpp).
inline constexpr uint64_t kMaxMeshFileVertices = 1ull << 23;
inline constexpr uint64_t kMaxMeshFileTriangles = 1ull << 23;

// Each throws Error prefixed with `where` ("mesh 'x': PLY 'file'") naming the header line,
// element, accessor, buffer view, buffer or node at fault.
// A PLY file is checked whole (its body against its header: assimp loops on a list count it
// cannot read); an OFF file by its header.
void check_ply(std::span<const std::byte> file, const std::string& where);
void check_off_header(std::span<const std::byte> file, const std::string& where);
// A .gltf (JSON) or .glb (binary container) file: its JSON's buffers, views, accessors, meshes,
// nodes and scenes. External buffers must be relative paths inside the file's folder; their
// sizes are checked when they are read (mesh_file.cpp).
// Returns each mesh primitive (in file order) with the triangles its indices (or positions)
// describe, so that the reader can tell when assimp drops some.
struct GltfPrimitive {
  std::string field;   // "meshes[2].primitives[0]"
  int64_t triangles;   // -1: not a triangle list (strips, fans, points, lines)
};
std::vector<GltfPrimitive> check_gltf(std::span<const std::byte> file, bool binary, const std::string& where);
// The JSON of a .gltf (the file) or .glb (its first chunk, the container's header checked);
// `bin_bytes` gets the .glb's binary chunk size (~0 when there is none).
std::string_view gltf_json_text(std::span<const std::byte> file, bool binary, const std::string& where,
                                uint64_t* bin_bytes = nullptr);

}  // namespace sdfbench
