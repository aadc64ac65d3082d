#pragma once
// Where generated and fetched meshes live: $SDFBENCH_MESH_CACHE, else
// $XDG_CACHE_HOME/sdfbench/meshes, else ~/.cache/sdfbench/meshes (sized_mesh.h's generated
// sizes, named_mesh.h's scans). Not committed.
#include <filesystem>

namespace sdfbench {

// The cache folder (created on first use by its writers); empty when none can be named (no HOME).
std::filesystem::path mesh_cache_dir();

}  // namespace sdfbench
