#pragma once
// Image textures and texture-coordinate tables in a scene's one texel table (Scene::texels):
// what the JSON loader's `texture` materials and the glTF loader's base colour textures share.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scenes/scene.h"

namespace sdfbench {

// Texels become linear RGBA floats, all of a scene's in one GPU texel buffer: 16 Mi of them
// (4096 x 4096, 256 MiB) stay far inside lavapipe's 128 Mi-element texel buffers and memory.
inline constexpr uint64_t kMaxSceneTexels = 1ull << 24;
inline constexpr uint64_t kMaxImageFileBytes = 256ull << 20;

// Decodes an image file's bytes into scene.texels as linear RGBA and returns its Texture:
// integer formats are display-encoded, so gamma 2.2 is undone; float formats are linear. Grey
// fills rgb; alpha is ignored. The header's size is checked against kMaxSceneTexels before any
// pixel is decoded (a 296 KB PNG can declare 16384 x 16384). `name` names it in errors (Error).
Texture add_texture(std::span<const std::byte> bytes, const std::filesystem::path& source, const std::string& name,
                    Scene& scene);

// Appends a mesh's per-triangle texture coordinates (`uv`, per vertex of mesh.triangles) to
// scene.texels, two texels per triangle ((uv0, uv1), (uv2, 0, 0)), and returns the first: the
// table Material::triangle_uvs names. v runs up the image, as assimp gives it (it flips glTF's)
// and the shading program reads it. Throws Error naming `name` past kMaxSceneTexels.
uint32_t add_triangle_uvs(const Mesh& mesh, const std::vector<glm::vec2>& uv, const std::string& name, Scene& scene);

}  // namespace sdfbench
