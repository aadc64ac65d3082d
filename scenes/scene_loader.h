#pragma once
#include <filesystem>
#include <string>

#include "scenes/scene.h"

namespace sdfbench {

// Reads a JSON scene descriptor (format: scenes/README.md). Every problem throws Error with
// the file, the field path (e.g. "instances[3].mesh") and what is wrong.
Scene load_scene_file(const std::filesystem::path& path);

// Same, from text already in memory; `origin` names it in errors and resolves relative paths.
Scene parse_scene_json(const std::string& text, const std::filesystem::path& origin);

}  // namespace sdfbench
