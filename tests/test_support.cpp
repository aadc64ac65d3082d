#include "tests/test_support.h"

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cstdio>
#include <fstream>
#include <random>

namespace sdfbench::test {

TempDir::TempDir() {
  static std::atomic<int> counter{0};
  path_ = std::filesystem::temp_directory_path() /
          ("sdfbench_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
  std::filesystem::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

std::filesystem::path TempDir::write(const std::string& name, const std::string& content) const {
  const std::filesystem::path p = path_ / name;
  std::ofstream(p, std::ios::binary) << content;
  return p;
}

CommandResult run_command(const std::string& command_line) {
  CommandResult result;
  const std::string command = command_line + " 2>&1";
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buffer;
  size_t n;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) result.output.append(buffer.data(), n);
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return result;
}

CommandResult run_shell(const std::string& shell_command, int seconds) {
  return run_command("timeout -k 5 " + std::to_string(seconds) + " bash -c '" + shell_command + "'");
}

CommandResult run_sdfbench(const std::string& args) { return run_command(std::string(SDFBENCH_BINARY) + " " + args); }

FrameImages render_frame(const std::string& backend, const Scene& scene, RenderMode mode, uint32_t width,
                         uint32_t height) {
  auto renderer = create_renderer(backend, BackendOptions{});
  renderer->prepare(scene);
  return renderer->render(FrameRequest{width, height, mode, true}).images;
}

}  // namespace sdfbench::test
