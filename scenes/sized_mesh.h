#pragma once
// Built-in meshes at a chosen size (scenes/mesh_resize.h), cached on disk: making a 1M-triangle
// mesh takes seconds, reading it back less. The folder is $SDFBENCH_MESH_CACHE, else
// $XDG_CACHE_HOME/sdfbench/meshes, else ~/.cache/sdfbench/meshes. A file is named by mesh, size
// and a digest of the source OBJ and the generator's version, written atomically (never half a
// file) with a first line naming the mesh and the digest of the rest, and made again when it is
// not a regular file (a symlink is never followed), its content does not match that digest, or it
// does not read back as what its name says. A cache that cannot be written is a warning. Not committed.
#include <cstdint>
#include <filesystem>
#include <string>

#include "scenes/mesh.h"
#include "scenes/mesh_cache_dir.h"

namespace sdfbench {

// Built-in mesh `name` ("bunny") at `triangles` (within kResizeTolerance). Prints a line on
// stderr when it generates one. Throws Error like resize_mesh.
Mesh load_sized_mesh(const std::string& name, uint32_t triangles);

}  // namespace sdfbench
