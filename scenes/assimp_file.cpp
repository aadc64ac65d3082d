#include "scenes/assimp_file.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include <assimp/IOSystem.hpp>
#include <assimp/MemoryIOWrapper.h>
#include <assimp/postprocess.h>

#include "scenes/mesh_file_check.h"
#include "util/error.h"
#include "util/input_file.h"

namespace sdfbench {
namespace {

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

}  // namespace

void append_triangles(const aiMesh& m, const aiMatrix4x4& world, Mesh& mesh, const std::string& where,
                      std::vector<glm::vec2>* uv) {
  if (mesh.positions.size() + m.mNumVertices > kMaxMeshFileVertices)
    throw Error(where + ": more than " + std::to_string(kMaxMeshFileVertices) + " vertices once its nodes place its meshes");
  const auto base = static_cast<uint32_t>(mesh.positions.size());
  for (unsigned v = 0; v < m.mNumVertices; ++v) {
    const aiVector3D p = world * m.mVertices[v];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw Error(where + ": mesh '" + printable(m.mName.C_Str()) + "' vertex " + std::to_string(v) +
                  " is not finite (where its node places it)");
    mesh.positions.emplace_back(p.x, p.y, p.z);
    if (!uv) continue;
    const aiVector3D t = m.HasTextureCoords(0) ? m.mTextureCoords[0][v] : aiVector3D();
    if (!(std::abs(t.x) <= kMaxTextureCoordinate && std::abs(t.y) <= kMaxTextureCoordinate))
      throw Error(where + ": mesh '" + printable(m.mName.C_Str()) + "' vertex " + std::to_string(v) +
                  ": its texture coordinate is not a finite number within +-" + std::to_string(int(kMaxTextureCoordinate)));
    uv->emplace_back(t.x, t.y);
  }
  // Polygons become fans (the files' polygons are convex: quads of scans and CAD meshes); points
  // and lines have nothing to hit.
  for (unsigned f = 0; f < m.mNumFaces; ++f) {
    const aiFace& face = m.mFaces[f];
    if (face.mNumIndices < 3) continue;
    for (unsigned c = 0; c < face.mNumIndices; ++c)
      if (face.mIndices[c] >= m.mNumVertices)
        throw Error(where + ": mesh '" + printable(m.mName.C_Str()) + "' face " + std::to_string(f) + " uses vertex " +
                    std::to_string(face.mIndices[c]) + " of " + std::to_string(m.mNumVertices));
    if (mesh.triangles.size() + face.mNumIndices - 2 > kMaxMeshFileTriangles)
      throw Error(where + ": more than " + std::to_string(kMaxMeshFileTriangles) + " triangles once its nodes place its meshes");
    for (unsigned c = 2; c < face.mNumIndices; ++c)
      mesh.triangles.emplace_back(base + face.mIndices[0], base + face.mIndices[c - 1], base + face.mIndices[c]);
  }
}

AssimpFile import_checked(std::span<const std::byte> bytes, const std::string& format, const std::string& where,
                          std::optional<std::filesystem::path> folder) {
  std::vector<GltfPrimitive> primitives;
  if (format == "ply") check_ply(bytes, where);
  else if (format == "off") check_off_header(bytes, where);
  else primitives = check_gltf(bytes, format == "glb", where);

  AssimpFile file;
  file.importer = std::make_unique<Assimp::Importer>();
  file.importer->SetIOHandler(new ConfinedIOSystem(std::move(folder)));  // the importer owns it
  try {
    // No post-processing but assimp's own validation: its steps trust the indices they are given
    // (a hostile PLY's face index crashed aiProcess_Triangulate in the fuzz target), so indices
    // are checked and polygons triangulated here (append_triangles).
    file.scene = file.importer->ReadFileFromMemory(bytes.data(), bytes.size(), aiProcess_ValidateDataStructure, format.c_str());
  } catch (const std::exception& e) {
    throw Error(where + ": cannot read it: " + printable(e.what()));
  }
  const char* why = file.importer->GetErrorString();
  if (!file.scene || (file.scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) || !file.scene->mRootNode)
    throw Error(where + ": cannot read it: " + (*why ? printable(why) : std::string("assimp gives no reason")));
  // assimp skips a glTF face with an index out of range (a warning no one sees): count the faces
  // (assimp orders its meshes its own way, so the totals of triangle-list primitives).
  int64_t expected = 0, made = 0;
  bool lists_only = !primitives.empty();
  for (const GltfPrimitive& p : primitives) {
    lists_only = lists_only && p.triangles >= 0;
    expected += p.triangles;
  }
  for (unsigned m = 0; m < file.scene->mNumMeshes; ++m) made += file.scene->mMeshes[m]->mNumFaces;
  if (lists_only && made < expected)
    throw Error(where + ": " + (primitives.size() == 1 ? primitives[0].field + ": " : std::string()) +
                std::to_string(expected - made) + " of " + std::to_string(expected) +
                " triangles have a vertex index out of range");
  return file;
}

}  // namespace sdfbench
