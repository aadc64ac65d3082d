#include "renderers/vulkan/shader_compiler.h"

#include <mutex>

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>

#include "renderers/vulkan/embedded_shaders.h"
#include "renderers/work_counters.h"
#include "util/error.h"

namespace sdfbench {
namespace {

// Resolves #include "x.glsl" against the embedded sources (which live for the program's life).
class EmbeddedIncluder : public glslang::TShader::Includer {
 public:
  IncludeResult* includeLocal(const char* name, const char*, size_t) override { return find(name); }
  IncludeResult* includeSystem(const char* name, const char*, size_t) override { return find(name); }
  void releaseInclude(IncludeResult* result) override { delete result; }

 private:
  IncludeResult* find(const char* name) {
    const auto& shaders = embedded_shaders();
    auto it = shaders.find(name);
    if (it == shaders.end()) return nullptr;
    return new IncludeResult(it->first, it->second.data(), it->second.size(), nullptr);
  }
};

EShLanguage stage_of(const std::string& name) {
  auto ends_with = [&](const char* suffix) {
    const std::string s(suffix);
    return name.size() >= s.size() && name.compare(name.size() - s.size(), s.size(), s) == 0;
  };
  if (ends_with(".comp")) return EShLangCompute;
  if (ends_with(".rgen")) return EShLangRayGen;
  if (ends_with(".rchit")) return EShLangClosestHit;
  if (ends_with(".rmiss")) return EShLangMiss;
  throw InternalError("no shader stage for '" + name + "'");
}

}  // namespace

std::vector<uint32_t> compile_shader(const std::string& name, const std::string& preamble) {
  static std::once_flag initialised;
  std::call_once(initialised, [] { glslang::InitializeProcess(); });

  const auto& shaders = embedded_shaders();
  auto it = shaders.find(name);
  if (it == shaders.end()) throw InternalError("no embedded shader named '" + name + "'");

  const EShLanguage stage = stage_of(name);
  glslang::TShader shader(stage);
  const char* source = it->second.data();
  const int length = static_cast<int>(it->second.size());
  const char* source_name = it->first.c_str();
  shader.setStringsWithLengthsAndNames(&source, &length, &source_name, 1);
  // glslang reads the preamble before the source, whose #version and #extension lines still count
  // as first: so it holds preprocessor lines only, the work counters' (every kernel gets them;
  // shading_types.glsl needs them) and then the caller's defines.
  const std::string defines = work_counter_glsl_prelude() + preamble;
  shader.setPreamble(defines.c_str());
  shader.setEnvInput(glslang::EShSourceGlsl, stage, glslang::EShClientVulkan, 100);
  shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_2);
  shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_5);
  const EShMessages messages = static_cast<EShMessages>(EShMsgSpvRules | EShMsgVulkanRules);
  EmbeddedIncluder includer;
  if (!shader.parse(GetDefaultResources(), 460, false, messages, includer))
    throw Error("GLSL compile of '" + name + "' failed:\n" + shader.getInfoLog());

  glslang::TProgram program;
  program.addShader(&shader);
  if (!program.link(messages)) throw Error("GLSL link of '" + name + "' failed:\n" + std::string(program.getInfoLog()));

  std::vector<uint32_t> spirv;
  glslang::SpvOptions options;
  options.validate = true;
  glslang::GlslangToSpv(*program.getIntermediate(stage), spirv, &options);
  return spirv;
}

}  // namespace sdfbench
