#include "scenes/gltf_scene.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include <assimp/IOStream.hpp>
#include <assimp/IOSystem.hpp>
#include <assimp/material.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>

#include "scenes/assimp_file.h"
#include "scenes/mesh_file.h"
#include "scenes/mesh_file_check.h"
#include "scenes/scene_texture.h"
#include "util/error.h"
#include "util/input_file.h"

namespace sdfbench {
namespace {

constexpr size_t kMaxInstances = 1u << 20;

glm::mat4 to_glm(const aiMatrix4x4& m) {
  return glm::transpose(glm::make_mat4(&m.a1));  // aiMatrix4x4 is row-major
}

// glTF's base colour factor, metallic-roughness and transmission as the shading program's
// materials: albedo = base colour (linear, as glTF stores it); a mirror weight only for smooth
// metal, reflectance = metallic x (1 - roughness); transmission and ior from
// KHR_materials_transmission and KHR_materials_ior. The base colour texture is read by
// Textures below.
Material to_material(const aiMaterial& m, size_t index) {
  Material material;
  aiString name;
  material.name = m.Get(AI_MATKEY_NAME, name) == AI_SUCCESS && name.length ? name.C_Str() : "material " + std::to_string(index);
  aiColor4D base(0.8f, 0.8f, 0.8f, 1.0f);
  if (aiGetMaterialColor(&m, AI_MATKEY_BASE_COLOR, &base) != AI_SUCCESS) aiGetMaterialColor(&m, AI_MATKEY_COLOR_DIFFUSE, &base);
  material.albedo = glm::clamp(glm::vec3(base.r, base.g, base.b), 0.0f, 1.0f);
  float metallic = 0.0f, roughness = 1.0f, transmission = 0.0f, ior = 1.5f;
  aiGetMaterialFloat(&m, AI_MATKEY_METALLIC_FACTOR, &metallic);
  aiGetMaterialFloat(&m, AI_MATKEY_ROUGHNESS_FACTOR, &roughness);
  aiGetMaterialFloat(&m, AI_MATKEY_TRANSMISSION_FACTOR, &transmission);
  aiGetMaterialFloat(&m, AI_MATKEY_REFRACTI, &ior);
  auto unit = [](float v) { return std::isfinite(v) ? std::clamp(v, 0.0f, 1.0f) : 0.0f; };
  material.reflectance = unit(metallic) * (1.0f - unit(roughness));
  material.transmission = std::min(unit(transmission), 1.0f - material.reflectance);
  material.ior = std::isfinite(ior) && ior >= 1.0f && ior <= 4.0f ? ior : 1.5f;
  return material;
}

// A glTF node's local matrix from its JSON (matrix, or translation x rotation x scale).
glm::mat4 local_matrix(const nlohmann::json& node) {
  auto numbers = [&](const char* key, size_t n, std::vector<float> fallback) {
    const auto it = node.find(key);
    if (it == node.end()) return fallback;
    std::vector<float> v;
    if (!it->is_array() || it->size() != n) throw Error(std::string(key) + ": expected " + std::to_string(n) + " numbers");
    for (const nlohmann::json& x : *it) {
      if (!x.is_number() || !std::isfinite(x.get<double>())) throw Error(std::string(key) + ": expected finite numbers");
      v.push_back(x.get<float>());
    }
    return v;
  };
  if (node.contains("matrix")) return glm::make_mat4(numbers("matrix", 16, {}).data());  // column-major, as glm
  const std::vector<float> t = numbers("translation", 3, {0, 0, 0}), r = numbers("rotation", 4, {0, 0, 0, 1}),
                           s = numbers("scale", 3, {1, 1, 1});
  const glm::quat q(r[3], r[0], r[1], r[2]);
  return glm::translate(glm::mat4(1.0f), {t[0], t[1], t[2]}) * glm::mat4_cast(glm::normalize(q)) *
         glm::scale(glm::mat4(1.0f), {s[0], s[1], s[2]});
}

// The default scene's first perspective camera (depth first, in file order), from the JSON: its
// node's world matrix and yfov (assimp's camera fields differ between its versions).
std::optional<Camera> file_camera(const nlohmann::json& root, const std::string& where) {
  const nlohmann::json empty = nlohmann::json::array();
  const nlohmann::json& nodes = root.contains("nodes") ? root["nodes"] : empty;
  const nlohmann::json& cameras = root.contains("cameras") ? root["cameras"] : empty;
  const nlohmann::json& scenes = root.contains("scenes") ? root["scenes"] : empty;
  if (scenes.empty()) return std::nullopt;
  const nlohmann::json& scene = scenes[root.value("scene", 0u)];
  if (!scene.contains("nodes")) return std::nullopt;
  // (node, parent's world) pairs; the graph is a checked forest, so this ends.
  std::vector<std::pair<size_t, glm::mat4>> stack;
  for (auto it = scene["nodes"].rbegin(); it != scene["nodes"].rend(); ++it) stack.emplace_back(it->get<size_t>(), glm::mat4(1.0f));
  while (!stack.empty()) {
    const auto [n, parent] = stack.back();
    stack.pop_back();
    glm::mat4 world;
    try {
      world = parent * local_matrix(nodes[n]);
    } catch (const Error& e) {
      throw Error(where + ": nodes[" + std::to_string(n) + "]." + e.what());
    }
    if (nodes[n].contains("camera")) {
      const nlohmann::json& camera = cameras[nodes[n]["camera"].get<size_t>()];
      if (camera.value("type", "") == "perspective" && camera.contains("perspective") &&
          camera["perspective"].contains("yfov") && camera["perspective"]["yfov"].is_number()) {
        const double yfov = camera["perspective"]["yfov"].get<double>();
        if (!(yfov > 0.0 && yfov < 3.1)) throw Error(where + ": cameras[" + nodes[n]["camera"].dump() + "].perspective.yfov: expected 0 < yfov < 3.1 radians");
        Camera c;
        c.position = glm::vec3(world * glm::vec4(0, 0, 0, 1));
        const glm::vec3 forward(world * glm::vec4(0, 0, -1, 0)), up(world * glm::vec4(0, 1, 0, 0));
        if (glm::length(forward) == 0.0f || glm::length(up) == 0.0f || glm::length(glm::cross(forward, up)) == 0.0f)
          throw Error(where + ": nodes[" + std::to_string(n) + "]: its transform flattens the camera");
        c.look_at = c.position + glm::normalize(forward);
        c.up = glm::normalize(up);
        c.fov_y_degrees = static_cast<float>(glm::degrees(yfov));
        return c;
      }
    }
    if (nodes[n].contains("children"))
      for (auto it = nodes[n]["children"].rbegin(); it != nodes[n]["children"].rend(); ++it)
        stack.emplace_back(it->get<size_t>(), world);
  }
  return std::nullopt;
}

// A camera that frames the scene's box from the front, above and to the right (45 degrees).
Camera framing(const Aabb& box) {
  const glm::vec3 centre = box.center();
  const float radius = std::max(0.5f * glm::length(box.extent()), 1e-6f);
  Camera c;
  c.look_at = centre;
  c.position = centre + glm::normalize(glm::vec3(0.6f, 0.45f, 1.0f)) * (1.15f * radius / std::sin(glm::radians(22.5f)));
  c.fov_y_degrees = 45.0f;
  return c;
}

// The materials' base colour textures (the glTF's baseColorTexture, else a diffuse texture),
// each decoded once into the scene's texel table when a mesh with texture coordinates uses it:
// an image embedded in a .glb or a data URI, or a file inside the .gltf's folder (read through
// the importer's confined file system).
class Textures {
 public:
  Textures(const AssimpFile& file, const std::string& where) : file_(file), where_(where) {}

  // The texture index of material `index`'s base colour image in `scene`, or none.
  std::optional<uint32_t> of(unsigned index, Scene& scene) {
    const aiMaterial& m = *file_.scene->mMaterials[index];
    aiString path;
    if (m.GetTexture(aiTextureType_BASE_COLOR, 0, &path) != AI_SUCCESS &&
        m.GetTexture(aiTextureType_DIFFUSE, 0, &path) != AI_SUCCESS)
      return std::nullopt;
    const std::string name = path.C_Str();
    if (const auto it = loaded_.find(name); it != loaded_.end()) return it->second;
    const std::string what = where_ + ": material '" + scene.materials[index].name + "': base colour texture '" + printable(name) + "'";
    std::vector<std::byte> bytes;
    if (const aiTexture* embedded = file_.scene->GetEmbeddedTexture(name.c_str())) {
      if (embedded->mHeight != 0) throw Error(what + ": an uncompressed embedded image (only PNG, JPEG and the other image files are read)");
      const auto* data = reinterpret_cast<const std::byte*>(embedded->pcData);
      bytes.assign(data, data + embedded->mWidth);
    } else {
      std::unique_ptr<Assimp::IOStream> stream(file_.importer->GetIOHandler()->Open(name.c_str(), "rb"));
      if (!stream) throw Error(what + ": not a readable file inside the scene's folder");
      bytes.resize(stream->FileSize());
      if (stream->Read(bytes.data(), 1, bytes.size()) != bytes.size()) throw Error(what + ": cannot read it");
    }
    try {
      scene.textures.push_back(add_texture(bytes, name, "image '" + printable(name) + "'", scene));
    } catch (const Error& e) {
      throw Error(what + ": " + e.what());
    }
    return loaded_[name] = static_cast<uint32_t>(scene.textures.size() - 1);
  }

 private:
  const AssimpFile& file_;
  const std::string& where_;
  std::map<std::string, uint32_t> loaded_;
};

struct Builder {
  const aiScene& ai;
  const std::string& where;
  Scene& scene;
  Textures textures;
  std::vector<int64_t> mesh_of;      // aiMesh -> scene mesh (-1: no triangles)
  std::vector<uint32_t> material_of;  // aiMesh -> scene material
  size_t triangles = 0;

  // The scene mesh of aiMesh `m`'s triangles, transformed by `world`, and the material its
  // instances use: a textured one of its own (its uv table) when its material has a base colour
  // texture and the mesh texture coordinates, else the file's material.
  std::pair<Mesh, uint32_t> make_mesh(unsigned m, const aiMatrix4x4& world, std::string name) {
    const aiMesh& source = *ai.mMeshes[m];
    Mesh mesh;
    mesh.name = std::move(name);
    count(source);
    const std::optional<uint32_t> texture =
        source.HasTextureCoords(0) ? textures.of(source.mMaterialIndex, scene) : std::nullopt;
    std::vector<glm::vec2> uv;
    append_triangles(source, world, mesh, where, texture ? &uv : nullptr);
    if (world.Determinant() < 0.0f)
      for (glm::uvec3& t : mesh.triangles) std::swap(t.y, t.z);  // a mirror keeps the faces' winding
    if (!texture || mesh.triangles.empty()) return {std::move(mesh), source.mMaterialIndex};
    Material material = scene.materials[source.mMaterialIndex];
    material.name += " on " + mesh.name;
    material.texture = *texture;
    material.texture_size = 1.0f;
    material.triangle_uvs = add_triangle_uvs(mesh, uv, where + ": mesh '" + printable(mesh.name) + "'", scene);
    scene.materials.push_back(std::move(material));
    return {std::move(mesh), static_cast<uint32_t>(scene.materials.size() - 1)};
  }

  // Instances of the node's meshes: a world matrix of rotation, uniform scale and translation is
  // an instance of the shared mesh; anything else (shear, non-uniform or negative scale) is
  // baked into a mesh of its own, since the SDF backends need distances that scale back exactly.
  void place(const aiNode& node, const aiMatrix4x4& parent, uint32_t depth) {
    if (depth > kMaxNodeDepth) throw Error(where + ": the node hierarchy is deeper than " + std::to_string(kMaxNodeDepth));
    const aiMatrix4x4 world = parent * node.mTransformation;
    for (unsigned k = 0; k < node.mNumMeshes; ++k) {
      const unsigned m = node.mMeshes[k];
      if (m >= ai.mNumMeshes) throw Error(where + ": a node names a mesh that does not exist");
      if (mesh_of[m] < 0) continue;
      if (scene.instances.size() == kMaxInstances)
        throw Error(where + ": more than " + std::to_string(kMaxInstances) + " mesh instances");
      Instance instance{.mesh = static_cast<uint32_t>(mesh_of[m]), .material = material_of[m]};
      aiVector3D scaling, position;
      aiQuaternion rotation;
      world.Decompose(scaling, rotation, position);
      const float lo = std::min({scaling.x, scaling.y, scaling.z}), hi = std::max({scaling.x, scaling.y, scaling.z});
      if (lo > 0.0f && hi <= lo * (1.0f + 1e-5f) && world.Determinant() > 0.0f) {
        instance.transform.translation = {position.x, position.y, position.z};
        instance.transform.rotation = glm::normalize(glm::quat(rotation.w, rotation.x, rotation.y, rotation.z));
        instance.transform.scale = (lo + hi) / 2;
      } else {
        auto [baked, material] =
            make_mesh(m, world, scene.meshes[static_cast<size_t>(mesh_of[m])].name + " (node " + printable(node.mName.C_Str()) + ")");
        baked.source = scene.meshes[static_cast<size_t>(mesh_of[m])].source;
        finish_mesh(baked);
        instance.material = material;
        instance.mesh = static_cast<uint32_t>(scene.meshes.size());
        scene.meshes.push_back(std::move(baked));
      }
      scene.instances.push_back(instance);
    }
    for (unsigned c = 0; c < node.mNumChildren; ++c) place(*node.mChildren[c], world, depth + 1);
  }

  void count(const aiMesh& m) {
    triangles += m.mNumFaces;
    if (triangles > kMaxMeshFileTriangles)
      throw Error(where + ": more than " + std::to_string(kMaxMeshFileTriangles) + " triangles in its meshes");
  }
};

}  // namespace

Scene load_gltf_scene(const std::filesystem::path& path) {
  const std::string format = mesh_file_format(path);
  const std::string where = "glTF scene '" + printable(path.string()) + "'";
  if (format != "gltf" && format != "glb") throw Error(where + ": not a .gltf or .glb file");
  const std::vector<std::byte> bytes = read_input_bytes(path, "glTF scene", kMaxMeshFileBytes);
  const AssimpFile file = import_checked(bytes, format, where, containing_folder(path));
  const aiScene& ai = *file.scene;

  Scene scene;
  scene.name = path.string();
  for (unsigned i = 0; i < ai.mNumMaterials; ++i) scene.materials.push_back(to_material(*ai.mMaterials[i], i));
  if (scene.materials.empty()) scene.materials.push_back(Material{.name = "default"});
  const size_t file_materials = scene.materials.size();
  Builder builder{ai, where, scene, Textures(file, where), std::vector<int64_t>(ai.mNumMeshes, -1),
                  std::vector<uint32_t>(ai.mNumMeshes, 0)};
  for (unsigned m = 0; m < ai.mNumMeshes; ++m) {
    if (ai.mMeshes[m]->mMaterialIndex >= file_materials)
      throw Error(where + ": mesh '" + printable(ai.mMeshes[m]->mName.C_Str()) + "' names a material that does not exist");
    auto [mesh, material] = builder.make_mesh(m, aiMatrix4x4(), ai.mMeshes[m]->mName.length ? ai.mMeshes[m]->mName.C_Str() : "mesh " + std::to_string(m));
    mesh.source = path;
    if (mesh.triangles.empty()) continue;  // points or lines only
    finish_mesh(mesh);
    builder.mesh_of[m] = static_cast<int64_t>(scene.meshes.size());
    builder.material_of[m] = material;
    scene.meshes.push_back(std::move(mesh));
  }
  builder.place(*ai.mRootNode, aiMatrix4x4(), 0);
  if (scene.instances.empty()) throw Error(where + ": its scene places no triangle mesh");

  // Punctual lights as the shading program's; none: a sun from above and the right. Colours are
  // scaled to at most 1 (glTF's intensities are in candela and lux).
  for (unsigned i = 0; i < ai.mNumLights; ++i) {
    const aiLight& l = *ai.mLights[i];
    const aiNode* node = ai.mRootNode->FindNode(l.mName);
    glm::mat4 world(1.0f);
    for (const aiNode* n = node; n; n = n->mParent) world = to_glm(n->mTransformation) * world;
    glm::vec3 colour(l.mColorDiffuse.r, l.mColorDiffuse.g, l.mColorDiffuse.b);
    const float peak = std::max({colour.x, colour.y, colour.z});
    if (!(peak > 0.0f) || !std::isfinite(peak)) continue;
    colour /= std::max(peak, 1.0f);
    if (l.mType == aiLightSource_DIRECTIONAL) {
      const glm::vec3 d(world * glm::vec4(l.mDirection.x, l.mDirection.y, l.mDirection.z, 0.0f));
      if (glm::length(d) > 0.0f) scene.lights.push_back(Light{.direction = -glm::normalize(d), .color = colour});
    } else if (l.mType == aiLightSource_POINT || l.mType == aiLightSource_SPOT) {
      scene.lights.push_back(Light{.kind = Light::Kind::Point,
                                   .position = glm::vec3(world * glm::vec4(l.mPosition.x, l.mPosition.y, l.mPosition.z, 1.0f)),
                                   .color = colour});
    }
  }
  if (scene.lights.empty()) scene.lights.push_back(Light{.direction = glm::normalize(glm::vec3(0.4f, 1.0f, 0.3f))});

  const nlohmann::json root = nlohmann::json::parse(gltf_json_text(bytes, format == "glb", where));  // checked above
  scene.camera = file_camera(root, where).value_or(framing(scene.bounds()));
  check_coordinates(scene);
  return scene;
}

}  // namespace sdfbench
