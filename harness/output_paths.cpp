#include "harness/output_paths.h"

#include <system_error>

#include "util/error.h"


namespace sdfbench {
namespace fs = std::filesystem;
namespace {

// Where a write to or a read of `path` lands: symlinks followed (a reader follows them; the
// atomic writer refuses one at the target, but an input reached through one is still that input).
fs::path resolved(const fs::path& path) {
  std::error_code ec;
  const fs::path p = fs::weakly_canonical(fs::absolute(path, ec), ec);
  return ec ? fs::absolute(path).lexically_normal() : p;
}

bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  if (fs::equivalent(a, b, ec) && !ec) return true;  // both exist: device and inode
  return resolved(a) == resolved(b);
}

std::string describe(const NamedPath& p) { return p.what + " '" + p.path.string() + "'"; }

}  // namespace

std::vector<NamedPath> scene_inputs(const Scene& scene) {
  std::vector<NamedPath> inputs;
  if (std::error_code ec; fs::is_regular_file(scene.name, ec)) inputs.push_back({"--scene", scene.name});
  for (const Mesh& mesh : scene.meshes)
    if (!mesh.source.empty()) inputs.push_back({"the scene's mesh", mesh.source});
  for (const Texture& texture : scene.textures)
    if (!texture.source.empty()) inputs.push_back({"the scene's texture", texture.source});
  return inputs;
}

void check_distinct_outputs(const std::vector<NamedPath>& outputs, const std::vector<NamedPath>& inputs) {
  for (size_t i = 0; i < outputs.size(); ++i) {
    if (outputs[i].path.empty()) continue;
    for (size_t j = 0; j < i; ++j)
      if (!outputs[j].path.empty() && same_file(outputs[i].path, outputs[j].path))
        throw Error(describe(outputs[i]) + " is the same file as " + describe(outputs[j]) +
                    ": one would overwrite the other; give each output its own path");
    for (const NamedPath& input : inputs)
      if (!input.path.empty() && same_file(outputs[i].path, input.path))
        throw Error(describe(outputs[i]) + " is " + describe(input) + ": writing it would destroy an input; choose another path");
  }
}

}  // namespace sdfbench
