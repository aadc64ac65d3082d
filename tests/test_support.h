#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "renderers/renderer.h"

namespace sdfbench::test {

// A fresh directory under the system temp dir, removed when the object dies.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path write(const std::string& name, const std::string& content) const;

 private:
  std::filesystem::path path_;
};

struct CommandResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

// Runs a whole shell command line; its stdout and stderr together.
CommandResult run_command(const std::string& command_line);

// `shell_command` (bash) under `timeout`: exit 124 when it runs past `seconds`, so a hang or a
// runaway fails the test instead of stalling it.
CommandResult run_shell(const std::string& shell_command, int seconds = 60);

// Runs the sdfbench binary with `args` (a shell-quoted string).
CommandResult run_sdfbench(const std::string& args);

// One frame of `scene` by `backend` with default options, read back.
FrameImages render_frame(const std::string& backend, const Scene& scene, RenderMode mode, uint32_t width,
                         uint32_t height);

// The strict agreement of the triangle backends with Embree (the issues' acceptance): hit and id
// >= 99.9 %, depth p99 <= 1e-4, PSNR >= 45 dB, and where both hit the same instance, the same
// triangle (ids in the mesh's own numbering). Records gtest failures.
void expect_agrees_with_embree(const std::string& backend, const Scene& scene, RenderMode mode, uint32_t width,
                               uint32_t height);

// Every registered backend but the reference (embree), for tests parameterised by backend, and
// a test-name suffix for each ("sdf-global" -> "sdf_global").
std::vector<std::string> backends_but_the_reference();
std::string backend_test_name(const std::string& backend);

// Every thesis mesh in every mode, for parameterised tests.
struct MeshMode {
  const char* mesh;
  RenderMode mode;
};
std::vector<MeshMode> thesis_meshes_in_every_mode();
std::string mesh_mode_name(const MeshMode& m);

}  // namespace sdfbench::test
