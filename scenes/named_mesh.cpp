#include "scenes/named_mesh.h"

#include <algorithm>

#include "scenes/mesh_file.h"
#include "scenes/mesh_cache_dir.h"
#include "util/error.h"

namespace sdfbench {

const std::vector<ScannedMesh>& scanned_meshes() {
  static const std::vector<ScannedMesh> scans = {
      {"stanford-bunny", "stanford-bunny.obj", 69666, "glmark2-data"},  // the Stanford bunny at full resolution
      {"armadillo", "armadillo.off", 52000, "libcgal-demo"},
      {"dragon", "ChineseDragon-10kv.off", 19994, "libcgal-demo"},
      {"elephant", "refined_elephant.off", 88928, "libcgal-demo"},
      {"bunny00", "bunny00.off", 75408, "libcgal-demo"},
  };
  return scans;
}

namespace {

const ScannedMesh* find_scan(const std::string& name) {
  for (const ScannedMesh& scan : scanned_meshes())
    if (name == scan.name) return &scan;
  return nullptr;
}

}  // namespace

bool is_mesh_name(const std::string& name) { return !builtin_mesh_path(name).empty() || find_scan(name); }

std::string mesh_names_text() {
  std::string text;
  for (const std::string& name : thesis_mesh_names()) text += (text.empty() ? "" : ", ") + name;
  text += "; scans (harness/scripts/fetch_scanned_meshes.sh): ";
  for (const ScannedMesh& scan : scanned_meshes()) text += std::string(scan.name) + (&scan == &scanned_meshes().back() ? "" : ", ");
  return text;
}

Mesh load_named_mesh(const std::string& name) {
  if (const std::filesystem::path builtin = builtin_mesh_path(name); !builtin.empty()) return load_obj(builtin, name);
  const ScannedMesh* scan = find_scan(name);
  if (!scan) throw Error("unknown mesh '" + name + "' (expected " + mesh_names_text() + ")");
  const std::filesystem::path cache = mesh_cache_dir();
  const std::filesystem::path file = cache.empty() ? std::filesystem::path() : cache / "scans" / scan->file;
  std::error_code ec;
  if (file.empty() || !std::filesystem::exists(file, ec))
    throw Error("mesh '" + name + "' is a scan from Debian's " + scan->package + " that is not fetched yet (looked for '" +
                file.string() + "'): run harness/scripts/fetch_scanned_meshes.sh");
  Mesh mesh = load_mesh_file(file, name);
  if (mesh.triangle_count() != scan->triangles)
    throw Error("mesh '" + name + "': '" + file.string() + "' holds " + std::to_string(mesh.triangle_count()) +
                " triangles, not the scan's " + std::to_string(scan->triangles) +
                " (fetch it again: harness/scripts/fetch_scanned_meshes.sh)");
  return mesh;
}

}  // namespace sdfbench
