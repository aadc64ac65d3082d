#include "scenes/sized_mesh.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <optional>
#include <string_view>

#include "scenes/mesh_resize.h"
#include "util/atomic_file.h"
#include "util/error.h"
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

// The OBJ body, then a first line naming the mesh and the digest of that body: the cache trusts a
// file only when its body still has the digest it was written with.
std::string obj_text(const Mesh& mesh) {
  std::string body;
  body.reserve(mesh.positions.size() * 40 + mesh.triangles.size() * 30);
  char line[96];
  for (const glm::vec3& p : mesh.positions) {
    std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", p.x, p.y, p.z);  // 9 digits: floats round-trip
    body += line;
  }
  for (const glm::uvec3& t : mesh.triangles) {
    std::snprintf(line, sizeof line, "f %u %u %u\n", t.x + 1, t.y + 1, t.z + 1);
    body += line;
  }
  return "# sdfbench: " + mesh.name + ", " + std::to_string(mesh.triangles.size()) + " triangles, " + kGeneratorVersion +
         ", digest " + hex(fnv1a64(body)) + "\n" + body;
}

bool within_tolerance(size_t got, uint32_t target) {
  return std::abs(static_cast<double>(got) - target) <= kResizeTolerance * target;
}

// The cached mesh at `file`, or why it cannot be used: not a regular file (a symlink is never
// followed), unreadable, its body not the one its digest line names (edited, truncated, another
// mesh), or not `triangles` triangles.
std::optional<Mesh> read_cached(const std::filesystem::path& file, const std::string& sized_name, uint32_t triangles,
                                std::string& why) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::symlink_status(file, ec);
  if (ec || status.type() == std::filesystem::file_type::not_found) return std::nullopt;
  if (status.type() != std::filesystem::file_type::regular) {
    why = "is not a regular file (a symbolic link or another kind), never followed";
    return std::nullopt;
  }
  try {
    const std::string text = read_input_file(file, "mesh cache file", uint64_t{1} << 30);
    const size_t eol = std::min(text.find('\n'), text.size());
    const std::string_view first_line = std::string_view(text).substr(0, eol);
    const std::string digest = ", digest " + hex(fnv1a64(std::string_view(text).substr(std::min(eol + 1, text.size()))));
    if (first_line.rfind("# sdfbench: " + sized_name + ",", 0) != 0 || !first_line.ends_with(digest)) {
      why = "does not match the digest it was written with (changed, truncated or another mesh)";
      return std::nullopt;
    }
    Mesh mesh = parse_obj(text, file, sized_name);
    if (within_tolerance(mesh.triangles.size(), triangles)) return mesh;
    why = "has " + std::to_string(mesh.triangles.size()) + " triangles";
  } catch (const Error& e) {
    why = std::string("cannot be read: ") + e.what();
  }
  return std::nullopt;
}

// Writes the made mesh to the cache; a cache that cannot be written (read-only, full, something in
// the way) costs the next run the making again, so it is a warning, not the end of the run.
void write_cached(const std::filesystem::path& dir, const std::filesystem::path& file, const Mesh& mesh) {
  try {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throw Error("folder '" + dir.string() + "': " + ec.message());
    const std::string text = obj_text(mesh);
    write_file_atomically(file, std::as_bytes(std::span(text.data(), text.size())));
    std::cerr << "mesh cache: " << mesh.name << " cached in " << file.string() << "\n";
  } catch (const Error& e) {
    std::cerr << "warning: mesh cache: " << mesh.name << " not cached (" << e.what()
              << "); the next run makes it again (set SDFBENCH_MESH_CACHE to a writable folder)\n";
  }
}

}  // namespace

Mesh load_sized_mesh(const std::string& name, uint32_t triangles) {
  const std::filesystem::path source = builtin_mesh_path(name);
  if (source.empty()) throw Error("unknown mesh '" + name + "' (expected bunny, teapot, monkey or sphere)");
  const std::string source_text = read_input_file(source, "OBJ", uint64_t{1} << 30);
  const std::string sized_name = name + "@" + std::to_string(triangles);
  const std::filesystem::path dir = mesh_cache_dir();
  const std::filesystem::path file =
      dir.empty() ? dir : dir / (sized_name + "-" + hex(fnv1a64(source_text, fnv1a64(kGeneratorVersion))) + ".obj");

  if (!file.empty()) {
    std::string why;
    if (std::optional<Mesh> cached = read_cached(file, sized_name, triangles, why)) return std::move(*cached);
    if (!why.empty()) std::cerr << "note: mesh cache '" << file.string() << "' " << why << "; making " << sized_name << " again\n";
  }

  const auto start = std::chrono::steady_clock::now();
  Mesh mesh = resize_mesh(load_obj(source, name), triangles);
  mesh.name = sized_name;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // A line of its own (not left open for "cached in"): a warning or error after it starts a line.
  std::cerr << "mesh " << sized_name << ": " << mesh.triangles.size() << " triangles made in " << seconds << " s"
            << (file.empty() ? " (not cached: no HOME or SDFBENCH_MESH_CACHE)" : "") << "\n";
  if (file.empty()) return mesh;
  write_cached(dir, file, mesh);
  // As every later run reads it: the same text, parsed.
  return parse_obj(obj_text(mesh), file, sized_name);
}

}  // namespace sdfbench
