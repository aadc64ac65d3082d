#pragma once
// Meshes by name, as specs and scene files name them: the thesis' four (built in, in
// scenes/meshes/) and real scans from Debian packages, which harness/scripts/fetch_scanned_meshes.sh
// unpacks into the mesh cache (scans/ under mesh_cache_dir(); never committed, never downloaded
// by sdfbench itself). scenes/README.md lists the scans, their packages and licences.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "scenes/mesh.h"

namespace sdfbench {

struct ScannedMesh {
  const char* name;       // as specs name it: thesis:armadillo:100
  const char* file;       // in the cache's scans/ folder
  uint32_t triangles;     // what the file holds (checked when it is read)
  const char* package;    // the Debian package it comes from
};
const std::vector<ScannedMesh>& scanned_meshes();

// Whether `name` is a thesis mesh or a scan (fetched or not).
bool is_mesh_name(const std::string& name);
// "bunny, teapot, monkey, sphere; scans: stanford-bunny, armadillo, ..." for messages.
std::string mesh_names_text();

// The mesh `name`; throws Error for an unknown name, or a scan that is not fetched yet (naming
// the script that fetches it) or whose file does not hold what it should.
Mesh load_named_mesh(const std::string& name);

}  // namespace sdfbench
