#pragma once
// A glTF 2.0 file as a whole scene (`--scene FILE.gltf|.glb`): its default scene's node
// hierarchy becomes instances (a mesh several nodes use is one mesh with several instances, as
// the thesis' scenes are), its first perspective camera the view, its materials the shading
// program's, its punctual lights the lights. scenes/README.md, "glTF scenes", lists what is mapped
// and what is not.
#include <filesystem>

#include "scenes/scene.h"

namespace sdfbench {

// Throws Error naming the file and the part at fault (as mesh_file.h's glTF reader does), and
// for scenes beyond the limits (kMaxMeshFileTriangles triangles in all meshes, 1 Mi instances).
Scene load_gltf_scene(const std::filesystem::path& path);

}  // namespace sdfbench
