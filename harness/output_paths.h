#pragma once
// A command's outputs must be files of their own: one path named twice (`--csv x --markdown x`,
// `--out` and `--aov` alike) would keep only the last write, and an output that is one of the
// command's inputs (the scene, its meshes and textures, a CSV being merged) would destroy it.
// Checked at start-up, before anything is built, rendered or written.
#include <filesystem>
#include <string>
#include <vector>

#include "scenes/scene.h"

namespace sdfbench {

struct NamedPath {
  std::string what;  // the option, e.g. "--out", or "the scene's texture"
  std::filesystem::path path;
};

// The files `scene` was read from: its descriptor (when it is a file), meshes and textures.
std::vector<NamedPath> scene_inputs(const Scene& scene);

// Throws Error naming both options and the path when two outputs are one file, or an output is an
// input. Paths are compared as the writer and reader would reach them: relative to the current
// folder, `..` and symlinked folders resolved, and existing files by identity (device and inode:
// hard links and a symlink at an input are caught too). Empty paths (an option not given) are skipped.
void check_distinct_outputs(const std::vector<NamedPath>& outputs, const std::vector<NamedPath>& inputs = {});

}  // namespace sdfbench
