#pragma once
// A mesh from a file, by its extension: Wavefront OBJ (.obj, or none) through the validating
// OBJ loader (mesh.h); PLY, OFF and glTF 2.0 (.gltf, .glb) through assimp, each checked before
// assimp reads it (mesh_file_check.h). A glTF file's meshes are placed by its node hierarchy and
// merged into one mesh; its materials and cameras are not read here (gltf_scene.h reads a whole
// scene). scenes/README.md lists what is read and the limits.
#include <cstddef>
#include <filesystem>
#include <span>
#include <string>

#include "scenes/mesh.h"

namespace sdfbench {

// Throws Error naming the file (and the header line, accessor, node... at fault) for an
// unknown extension, an unreadable, oversized or malformed file, an external glTF buffer outside
// the file's folder, more than 8 Mi vertices or triangles, a non-finite coordinate or no triangle.
Mesh load_mesh_file(const std::filesystem::path& path, const std::string& name);

// The same from bytes in memory (the fuzz targets); `format` is "ply", "off", "gltf" or "glb".
// External glTF buffers are refused (there is no folder).
Mesh parse_mesh_bytes(std::span<const std::byte> bytes, const std::string& format, const std::filesystem::path& source,
                      const std::string& name);

// The extensions load_mesh_file reads, for messages: ".obj, .ply, .off, .gltf, .glb".
const char* mesh_file_extensions();
// A path's extension, lower case, without the dot ("glb"); the folder holding it (symlinks resolved).
std::string mesh_file_format(const std::filesystem::path& path);
std::filesystem::path containing_folder(const std::filesystem::path& path);

}  // namespace sdfbench
