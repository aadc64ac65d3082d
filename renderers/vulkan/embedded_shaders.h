#pragma once
#include <map>
#include <string>
#include <string_view>

namespace sdfbench {

// GLSL sources by file name (generated at build time by cmake/embed_shaders.cmake).
const std::map<std::string, std::string_view>& embedded_shaders();

}  // namespace sdfbench
