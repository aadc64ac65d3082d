#include "scenes/mesh_file.h"

#include <cmath>
#include <cstring>
#include <memory>
#include <optional>
#include <vector>

#include <assimp/Importer.hpp>
#include <assimp/IOSystem.hpp>
#include <assimp/MemoryIOWrapper.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "scenes/mesh_file_check.h"
#include "util/error.h"
#include "util/input_file.h"

namespace sdfbench {
namespace {

constexpr uint64_t kMaxMeshFileBytes = 512ull << 20;  // as an OBJ
constexpr uint32_t kMaxNodeDepth = 256;

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext.empty() ? ext : ext.substr(1);
}

// The files assimp may open besides the one in memory (a .gltf's external buffers): relative
// names inside `folder`, each read through InputFile (a regular file, size-capped). Without a
// folder (bytes from memory) there are none.
class ConfinedIOSystem : public Assimp::IOSystem {
 public:
  explicit ConfinedIOSystem(std::optional<std::filesystem::path> folder) : folder_(std::move(folder)) {}

  bool Exists(const char* file) const override { return resolve(file).has_value(); }
  char getOsSeparator() const override { return '/'; }
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    if (std::strchr(mode, 'w') || std::strchr(mode, 'a')) return nullptr;
    const std::optional<std::filesystem::path> path = resolve(file);
    if (!path) return nullptr;
    const std::vector<std::byte> bytes = read_input_bytes(*path, "glTF buffer", kMaxMeshFileBytes);
    auto* copy = new uint8_t[bytes.size() + 1];  // the stream owns it (delete[])
    std::memcpy(copy, bytes.data(), bytes.size());
    return new Assimp::MemoryIOStream(copy, bytes.size(), /*own=*/true);
  }
  void Close(Assimp::IOStream* stream) override { delete stream; }

 private:
  // `file` inside the folder (symlinks resolved), or nothing.
  std::optional<std::filesystem::path> resolve(const char* file) const {
    if (!folder_) return std::nullopt;
    std::error_code ec;
    const std::filesystem::path path = std::filesystem::weakly_canonical(*folder_ / file, ec);
    if (ec) return std::nullopt;
    const auto [end, _] = std::mismatch(folder_->begin(), folder_->end(), path.begin(), path.end());
    if (end != folder_->end() || !std::filesystem::is_regular_file(path, ec)) return std::nullopt;
    return path;
  }
  std::optional<std::filesystem::path> folder_;
};

// Appends every mesh the node and its descendants place, transformed by their world matrices.
void append_node(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent, uint32_t depth, Mesh& mesh,
                 const std::string& where) {
  if (depth > kMaxNodeDepth) throw Error(where + ": the node hierarchy is deeper than " + std::to_string(kMaxNodeDepth));
  const aiMatrix4x4 world = parent * node.mTransformation;
  for (unsigned k = 0; k < node.mNumMeshes; ++k) {
    if (node.mMeshes[k] >= scene.mNumMeshes) throw Error(where + ": a node names a mesh that does not exist");
    const aiMesh& m = *scene.mMeshes[node.mMeshes[k]];
    if (mesh.positions.size() + m.mNumVertices > kMaxMeshFileVertices)
      throw Error(where + ": more than " + std::to_string(kMaxMeshFileVertices) + " vertices once its nodes place its meshes");
    const auto base = static_cast<uint32_t>(mesh.positions.size());
    for (unsigned v = 0; v < m.mNumVertices; ++v) {
      const aiVector3D p = world * m.mVertices[v];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
        throw Error(where + ": mesh '" + printable(m.mName.C_Str()) + "' vertex " + std::to_string(v) +
                    " is not finite (where its node places it)");
      mesh.positions.emplace_back(p.x, p.y, p.z);
    }
    // Polygons become fans (the files' polygons are convex: quads of scans and CAD meshes); points
    // and lines have nothing to hit.
    for (unsigned f = 0; f < m.mNumFaces; ++f) {
      const aiFace& face = m.mFaces[f];
      if (face.mNumIndices < 3) continue;
      for (unsigned c = 0; c < face.mNumIndices; ++c)
        if (face.mIndices[c] >= m.mNumVertices)
          throw Error(where + ": mesh '" + printable(m.mName.C_Str()) + "' face " + std::to_string(f) +
                      " uses vertex " + std::to_string(face.mIndices[c]) + " of " + std::to_string(m.mNumVertices));
      if (mesh.triangles.size() + face.mNumIndices - 2 > kMaxMeshFileTriangles)
        throw Error(where + ": more than " + std::to_string(kMaxMeshFileTriangles) +
                    " triangles once its nodes place its meshes");
      for (unsigned c = 2; c < face.mNumIndices; ++c)
        mesh.triangles.emplace_back(base + face.mIndices[0], base + face.mIndices[c - 1], base + face.mIndices[c]);
    }
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c) append_node(scene, *node.mChildren[c], world, depth + 1, mesh, where);
}

Mesh import(std::span<const std::byte> bytes, const std::string& format, const std::filesystem::path& source,
            const std::string& name, std::optional<std::filesystem::path> folder) {
  const std::string kind = format == "glb" ? "glTF" : format == "gltf" ? "glTF" : format == "ply" ? "PLY" : "OFF";
  const std::string where = "mesh '" + printable(name) + "': " + kind + " '" + printable(source.string()) + "'";
  if (format == "ply") check_ply(bytes, where);
  else if (format == "off") check_off_header(bytes, where);
  else check_gltf(bytes, format == "glb", where);

  Assimp::Importer importer;
  importer.SetIOHandler(new ConfinedIOSystem(std::move(folder)));  // the importer owns it
  const aiScene* scene = nullptr;
  try {
    // No post-processing but assimp's own validation: its steps trust the indices they are given
    // (a hostile PLY's face index crashed aiProcess_Triangulate in the fuzz target), so indices
    // are checked and polygons triangulated here (append_node).
    scene = importer.ReadFileFromMemory(bytes.data(), bytes.size(), aiProcess_ValidateDataStructure, format.c_str());
  } catch (const std::exception& e) {
    throw Error(where + ": cannot read it: " + printable(e.what()));
  }
  if (!scene || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) || !scene->mRootNode)
    throw Error(where + ": cannot read it: " + printable(importer.GetErrorString()));
  Mesh mesh;
  mesh.name = name;
  mesh.source = source;
  append_node(*scene, *scene->mRootNode, aiMatrix4x4(), 0, mesh, where);
  if (mesh.triangles.empty()) throw Error(where + " contains no triangles");
  finish_mesh(mesh);
  return mesh;
}

}  // namespace

const char* mesh_file_extensions() { return ".obj, .ply, .off, .gltf, .glb"; }

Mesh parse_mesh_bytes(std::span<const std::byte> bytes, const std::string& format, const std::filesystem::path& source,
                      const std::string& name) {
  return import(bytes, format, source, name, std::nullopt);
}

Mesh load_mesh_file(const std::filesystem::path& path, const std::string& name) {
  const std::string format = lower_extension(path);
  if (format == "obj") return load_obj(path, name);
  if (format != "ply" && format != "off" && format != "gltf" && format != "glb")
    throw Error("mesh '" + printable(name) + "': '" + printable(path.string()) + "' is not a mesh file sdfbench reads (" +
                mesh_file_extensions() + ")");
  const std::vector<std::byte> bytes = read_input_bytes(path, "mesh file", kMaxMeshFileBytes);
  std::error_code ec;
  std::filesystem::path folder = std::filesystem::weakly_canonical(std::filesystem::absolute(path, ec), ec).parent_path();
  return import(bytes, format, path, name, std::move(folder));
}

}  // namespace sdfbench
