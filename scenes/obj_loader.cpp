#include <cmath>
#include <sstream>

#include <tiny_obj_loader.h>

#include "scenes/error.h"
#include "scenes/mesh.h"

namespace sdfbench {

Mesh load_obj(const std::filesystem::path& path, const std::string& name) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw Error("mesh '" + name + "': file '" + path.string() + "' does not exist or is not a file");

  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  config.mtl_search_path = "";  // materials come from the scene descriptor, not .mtl files
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(path.string(), config))
    throw Error("mesh '" + name + "': cannot read OBJ '" + path.string() + "': " + reader.Error());

  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  Mesh mesh;
  mesh.name = name;
  mesh.source = path;
  const size_t vertex_count = attrib.vertices.size() / 3;
  mesh.positions.resize(vertex_count);
  for (size_t i = 0; i < vertex_count; ++i) {
    const glm::vec3 p(attrib.vertices[3 * i], attrib.vertices[3 * i + 1], attrib.vertices[3 * i + 2]);
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw Error("mesh '" + name + "': OBJ '" + path.string() + "': vertex " + std::to_string(i + 1) +
                  " is not a finite number");
    mesh.positions[i] = p;
  }
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    const auto& indices = shape.mesh.indices;
    size_t offset = 0;
    for (size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
      const unsigned fv = shape.mesh.num_face_vertices[f];
      if (fv != 3)  // triangulation can leave lines/points out of faces; reject anything else
        throw Error("mesh '" + name + "': OBJ '" + path.string() + "': face " + std::to_string(f + 1) +
                    " of shape '" + shape.name + "' has " + std::to_string(fv) + " vertices after triangulation");
      glm::uvec3 tri;
      for (unsigned k = 0; k < 3; ++k) {
        const int index = indices[offset + k].vertex_index;
        if (index < 0 || static_cast<size_t>(index) >= vertex_count) {
          std::ostringstream msg;
          msg << "mesh '" << name << "': OBJ '" << path.string() << "': face " << (f + 1) << " of shape '"
              << shape.name << "' uses vertex index " << (index + 1) << " but the file has " << vertex_count
              << " vertices";
          throw Error(msg.str());
        }
        tri[k] = static_cast<unsigned>(index);
      }
      offset += fv;
      mesh.triangles.push_back(tri);
    }
  }
  if (mesh.triangles.empty())
    throw Error("mesh '" + name + "': OBJ '" + path.string() + "' contains no triangles");
  finish_mesh(mesh);
  return mesh;
}

}  // namespace sdfbench
