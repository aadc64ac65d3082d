#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace sdfbench {

// Compiles an embedded GLSL compute shader (and its #includes) to SPIR-V with glslang.
// Throws Error with glslang's log on failure.
std::vector<uint32_t> compile_compute_shader(const std::string& name, const std::string& preamble = "");

}  // namespace sdfbench
