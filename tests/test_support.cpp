#include "renderers/backend_registry.h"
#include "tests/test_support.h"

#include <gtest/gtest.h>

#include "harness/image_agreement.h"
#include "renderers/shading/gpu_types.h"

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

void expect_agrees_with_embree(const std::string& backend, const Scene& scene, RenderMode mode, uint32_t width,
                               uint32_t height) {
  const FrameImages reference = render_frame("embree", scene, mode, width, height);
  const FrameImages images = render_frame(backend, scene, mode, width, height);
  size_t instance_pixels = 0, same_instance = 0, same_triangle = 0;
  for (size_t i = 0; i < reference.instance_id.size(); ++i) {
    const bool instance = reference.instance_id[i] < shading::FLOOR_INSTANCE_VALUE;
    instance_pixels += instance;
    if (instance && images.instance_id[i] == reference.instance_id[i]) {
      ++same_instance;
      same_triangle += images.primitive_id[i] == reference.primitive_id[i];
    }
  }
  EXPECT_GT(instance_pixels, 0u) << "the frame shows no instance";
  const Agreement g = compare_frames(images, reference);
  EXPECT_GE(g.hit_percent, 99.9) << backend;
  EXPECT_GE(g.id_percent, 99.9) << backend;
  EXPECT_LE(g.depth_p99, 1e-4) << backend;
  EXPECT_GE(g.psnr, 45.0) << backend;
  EXPECT_GE(static_cast<double>(same_triangle), 0.999 * static_cast<double>(same_instance)) << backend;
}

std::vector<MeshMode> thesis_meshes_in_every_mode() {
  std::vector<MeshMode> cases;
  for (const char* mesh : {"bunny", "teapot", "monkey", "sphere"})
    for (RenderMode mode : {RenderMode::Primary, RenderMode::Shadow, RenderMode::Whitted}) cases.push_back({mesh, mode});
  return cases;
}

std::string mesh_mode_name(const MeshMode& m) { return std::string(m.mesh) + "_" + to_string(m.mode); }

std::vector<std::string> backends_but_the_reference() {
  std::vector<std::string> names;
  for (const std::string& name : backend_names())
    if (name != "embree") names.push_back(name);
  return names;
}

std::string backend_test_name(const std::string& backend) {
  std::string name = backend;
  for (char& c : name)
    if (c == '-') c = '_';
  return name;
}

}  // namespace sdfbench::test
