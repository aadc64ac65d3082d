#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace sdfbench {

// Compiles an embedded GLSL shader (and its #includes) to SPIR-V 1.5 with glslang; the stage
// follows the name: .comp, .rgen, .rchit or .rmiss; `preamble` (#defines) and, before it, the work
// counters' (work_counter_glsl_prelude(), renderers/work_counters.h) are read before the source
// (whose #version stays first). Throws Error with glslang's log on failure.
std::vector<uint32_t> compile_shader(const std::string& name, const std::string& preamble = "");

}  // namespace sdfbench
