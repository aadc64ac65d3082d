#include "scenes/mesh_file.h"

#include <cctype>
#include <vector>

#include "scenes/assimp_file.h"
#include "util/error.h"
#include "util/input_file.h"

namespace sdfbench {
namespace {

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext.empty() ? ext : ext.substr(1);
}

// Appends every mesh the node and its descendants place, transformed by their world matrices.
void append_node(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent, uint32_t depth, Mesh& mesh,
                 const std::string& where) {
  if (depth > kMaxNodeDepth) throw Error(where + ": the node hierarchy is deeper than " + std::to_string(kMaxNodeDepth));
  const aiMatrix4x4 world = parent * node.mTransformation;
  for (unsigned k = 0; k < node.mNumMeshes; ++k) {
    if (node.mMeshes[k] >= scene.mNumMeshes) throw Error(where + ": a node names a mesh that does not exist");
    append_triangles(*scene.mMeshes[node.mMeshes[k]], world, mesh, where);
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c) append_node(scene, *node.mChildren[c], world, depth + 1, mesh, where);
}

Mesh import(std::span<const std::byte> bytes, const std::string& format, const std::filesystem::path& source,
            const std::string& name, std::optional<std::filesystem::path> folder) {
  const std::string kind = format == "glb" || format == "gltf" ? "glTF" : format == "ply" ? "PLY" : "OFF";
  const std::string where = "mesh '" + printable(name) + "': " + kind + " '" + printable(source.string()) + "'";
  const AssimpFile file = import_checked(bytes, format, where, std::move(folder));
  Mesh mesh;
  mesh.name = name;
  mesh.source = source;
  append_node(*file.scene, *file.scene->mRootNode, aiMatrix4x4(), 0, mesh, where);
  if (mesh.triangles.empty()) throw Error(where + " contains no triangles");
  finish_mesh(mesh);
  return mesh;
}

}  // namespace

const char* mesh_file_extensions() { return ".obj, .ply, .off, .gltf, .glb"; }

std::string mesh_file_format(const std::filesystem::path& path) { return lower_extension(path); }

std::filesystem::path containing_folder(const std::filesystem::path& path) {
  std::error_code ec;
  return std::filesystem::weakly_canonical(std::filesystem::absolute(path, ec), ec).parent_path();
}

Mesh parse_mesh_bytes(std::span<const std::byte> bytes, const std::string& format, const std::filesystem::path& source,
                      const std::string& name) {
  return import(bytes, format, source, name, std::nullopt);
}

Mesh load_mesh_file(const std::filesystem::path& path, const std::string& name) {
  const std::string format = lower_extension(path);
  if (format == "obj" || format.empty()) return load_obj(path, name);  // no extension: OBJ, as before other formats
  if (format != "ply" && format != "off" && format != "gltf" && format != "glb")
    throw Error("mesh '" + printable(name) + "': '" + printable(path.string()) + "' is not a mesh file sdfbench reads (" +
                mesh_file_extensions() + ")");
  const std::vector<std::byte> bytes = read_input_bytes(path, "mesh file", kMaxMeshFileBytes);
  return import(bytes, format, path, name, containing_folder(path));
}

}  // namespace sdfbench
