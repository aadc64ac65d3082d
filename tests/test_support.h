#pragma once
#include <filesystem>
#include <string>

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

}  // namespace sdfbench::test
