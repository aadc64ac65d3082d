#include "scenes/mesh.h"

#include <cstdlib>

namespace sdfbench {

void finish_mesh(Mesh& mesh) {
  mesh.bounds = {};
  for (const glm::vec3& p : mesh.positions) mesh.bounds.extend(p);
  mesh.normals.assign(mesh.positions.size(), glm::vec3(0.0f));
  // Angle-weighted normals (Thürrner & Wüthrich 1998): independent of how faces are split.
  for (const glm::uvec3& t : mesh.triangles) {
    const glm::vec3 p[3] = {mesh.positions[t.x], mesh.positions[t.y], mesh.positions[t.z]};
    const glm::vec3 face = glm::cross(p[1] - p[0], p[2] - p[0]);
    const float len = glm::length(face);
    if (len == 0.0f) continue;
    for (int k = 0; k < 3; ++k) {
      const glm::vec3 a = p[(k + 1) % 3] - p[k], b = p[(k + 2) % 3] - p[k];
      const float la = glm::length(a), lb = glm::length(b);
      if (la == 0.0f || lb == 0.0f) continue;
      const float angle = std::acos(glm::clamp(glm::dot(a, b) / (la * lb), -1.0f, 1.0f));
      mesh.normals[t[k]] += angle * (face / len);
    }
  }
  for (glm::vec3& n : mesh.normals) {
    const float len = glm::length(n);
    n = len > 0.0f ? n / len : glm::vec3(0.0f, 1.0f, 0.0f);
  }
}

std::filesystem::path data_dir() {
  if (const char* env = std::getenv("SDFBENCH_DATA_DIR"); env && *env) return env;
  return SDFBENCH_DATA_DIR;
}

const std::vector<std::string>& thesis_mesh_names() {
  static const std::vector<std::string> names = {"bunny", "teapot", "monkey", "sphere"};
  return names;
}

std::filesystem::path builtin_mesh_path(const std::string& name) {
  for (const std::string& known : thesis_mesh_names())
    if (known == name) return data_dir() / "meshes" / (name + ".obj");
  return {};
}

}  // namespace sdfbench
