#include "scenes/scene_texture.h"

#include "util/error.h"
#include "util/image_codec.h"
#include "util/input_file.h"

namespace sdfbench {
namespace {

void check_room(const Scene& scene, uint64_t texels, const std::string& what) {
  if (scene.texels.size() + texels > kMaxSceneTexels)
    throw Error(what + (scene.texels.empty() ? "" : " (plus " + std::to_string(scene.texels.size()) + " in other textures)") +
                ", more than the " + std::to_string(kMaxSceneTexels) + " texels a scene may hold (4096x4096, " +
                describe_bytes(kMaxSceneTexels * sizeof(glm::vec4)) + " as RGBA floats)");
}

}  // namespace

Texture add_texture(std::span<const std::byte> bytes, const std::filesystem::path& source, const std::string& name,
                    Scene& scene) {
  const ImageHeader header = read_image_header(bytes, name);
  if (header.width > kMaxImageSide || header.height > kMaxImageSide)
    throw Error(name + " must have sides between 1 and " + std::to_string(kMaxImageSide));
  check_room(scene, uint64_t(header.width) * uint64_t(header.height),
             name + " is " + std::to_string(header.width) + "x" + std::to_string(header.height) + " texels");
  const DecodedImage image = decode_image(bytes, name);
  const uint32_t channels = image.header.channels;
  Texture texture{source, static_cast<uint32_t>(scene.texels.size()), image.header.width, image.header.height};
  for (size_t i = 0; i < image.pixels.size(); i += channels) {
    const float* p = &image.pixels[i];
    glm::vec3 rgb = channels >= 3 ? glm::vec3(p[0], p[1], p[2]) : glm::vec3(p[0]);  // grey (+ alpha) or RGB(A)
    if (!image.linear) rgb = glm::pow(glm::max(rgb, 0.0f), glm::vec3(2.2f));
    scene.texels.emplace_back(rgb, 1.0f);
  }
  return texture;
}

uint32_t add_triangle_uvs(const Mesh& mesh, const std::vector<glm::vec2>& uv, const std::string& name, Scene& scene) {
  check_room(scene, 2 * uint64_t(mesh.triangle_count()),
             name + "'s texture coordinates are " + std::to_string(2 * uint64_t(mesh.triangle_count())) + " texels");
  const auto first = static_cast<uint32_t>(scene.texels.size());
  for (const glm::uvec3& t : mesh.triangles) {
    scene.texels.emplace_back(uv.at(t.x), uv.at(t.y));
    scene.texels.emplace_back(uv.at(t.z), 0.0f, 0.0f);
  }
  return first;
}

}  // namespace sdfbench
