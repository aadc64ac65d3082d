#include "scenes/sized_mesh.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>

#include "scenes/error.h"
#include "scenes/mesh_resize.h"
#include "util/atomic_file.h"
#include "util/fnv1a.h"
#include "util/input_file.h"

namespace sdfbench {
namespace {

// Bump when resize_mesh's output changes: older cache files are then not found by name.
constexpr const char* kGeneratorVersion = "loop-openmesh9+meshopt0.18-v1";

std::string hex(uint64_t v) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(v));
  return text;
}

std::string obj_text(const Mesh& mesh) {
  std::string out = "# sdfbench: " + mesh.name + ", " + std::to_string(mesh.triangles.size()) + " triangles, " + kGeneratorVersion + "\n";
  out.reserve(mesh.positions.size() * 40 + mesh.triangles.size() * 30);
  char line[96];
  for (const glm::vec3& p : mesh.positions) {
    std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", p.x, p.y, p.z);  // 9 digits: floats round-trip
    out += line;
  }
  for (const glm::uvec3& t : mesh.triangles) {
    std::snprintf(line, sizeof line, "f %u %u %u\n", t.x + 1, t.y + 1, t.z + 1);
    out += line;
  }
  return out;
}

bool within_tolerance(size_t got, uint32_t target) {
  return std::abs(static_cast<double>(got) - target) <= kResizeTolerance * target;
}

}  // namespace

std::filesystem::path mesh_cache_dir() {
  if (const char* env = std::getenv("SDFBENCH_MESH_CACHE"); env && *env) return env;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::filesystem::path(xdg) / "sdfbench" / "meshes";
  if (const char* home = std::getenv("HOME"); home && *home) return std::filesystem::path(home) / ".cache" / "sdfbench" / "meshes";
  return {};
}

Mesh load_sized_mesh(const std::string& name, uint32_t triangles) {
  const std::filesystem::path source = builtin_mesh_path(name);
  if (source.empty()) throw Error("unknown mesh '" + name + "' (expected bunny, teapot, monkey or sphere)");
  const std::string source_text = read_input_file(source, "OBJ", uint64_t{1} << 30);
  const std::string sized_name = name + "@" + std::to_string(triangles);
  const std::filesystem::path dir = mesh_cache_dir();
  const std::filesystem::path file =
      dir.empty() ? dir : dir / (sized_name + "-" + hex(fnv1a64(source_text, fnv1a64(kGeneratorVersion))) + ".obj");

  if (!file.empty() && std::filesystem::is_regular_file(file)) {
    try {
      Mesh mesh = load_obj(file, sized_name);
      if (within_tolerance(mesh.triangles.size(), triangles)) return mesh;
    } catch (const Error&) {
    }
    std::cerr << "note: mesh cache '" << file.string() << "' is not a valid " << sized_name << "; making it again\n";
  }

  const auto start = std::chrono::steady_clock::now();
  Mesh mesh = resize_mesh(load_obj(source, name), triangles);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cerr << "mesh " << sized_name << ": " << mesh.triangles.size() << " triangles made in " << seconds << " s";
  if (file.empty()) {
    std::cerr << " (not cached: no HOME or SDFBENCH_MESH_CACHE)\n";
    return mesh;
  }
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw Error("mesh cache folder '" + dir.string() + "': " + ec.message() + " (set SDFBENCH_MESH_CACHE)");
  const std::string text = obj_text(mesh);
  write_file_atomically(file, std::as_bytes(std::span(text.data(), text.size())));
  std::cerr << ", cached in " << file.string() << "\n";
  return load_obj(file, sized_name);  // as every later run will read it
}

}  // namespace sdfbench
