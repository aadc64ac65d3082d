#pragma once
// A triangle mesh as every backend sees it: shared by all of its instances.
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scenes/aabb.h"

namespace sdfbench {

struct Mesh {
  std::string name;
  std::filesystem::path source;       // the file it was read from
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;      // per vertex, angle-weighted (same count as positions)
  std::vector<glm::uvec3> triangles;   // indices into positions, all checked in range
  Aabb bounds;

  size_t triangle_count() const { return triangles.size(); }
};

// Fills normals (angle-weighted vertex normals) and bounds from positions and triangles.
void finish_mesh(Mesh& mesh);

// Reads a Wavefront OBJ (polygons are triangulated). Throws Error naming the file, the line and
// the problem for unreadable or special files, coordinates that are not finite numbers,
// out-of-range indices, more than 8 Mi vertices or triangles, or empty meshes.
Mesh load_obj(const std::filesystem::path& path, const std::string& name);

// Same, from OBJ text already in memory (the fuzz target); `source` names it in errors.
Mesh parse_obj(const std::string& text, const std::filesystem::path& source, const std::string& name);

// The directory holding scenes/ (meshes, descriptors): $SDFBENCH_DATA_DIR or the source tree.
std::filesystem::path data_dir();

// The four thesis meshes, by the names the thesis uses.
const std::vector<std::string>& thesis_mesh_names();

// Resolves a built-in mesh name ("bunny") to scenes/meshes/bunny.obj; returns empty if unknown.
std::filesystem::path builtin_mesh_path(const std::string& name);

}  // namespace sdfbench
