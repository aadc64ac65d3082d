// The command line, as a user meets it: clear errors and non-zero exits, never a crash.
#include <filesystem>

#include <gtest/gtest.h>

#include "tests/test_support.h"

namespace sdfbench {
namespace {

using test::run_sdfbench;

// A user error: exit 1 with "sdfbench: error:" and the expected words; not a signal/crash.
void expect_user_error(const std::string& args, const std::string& words) {
  const test::CommandResult r = run_sdfbench(args);
  EXPECT_EQ(r.exit_code, 1) << args << "\n" << r.output;
  EXPECT_NE(r.output.find("sdfbench: error:"), std::string::npos) << args << "\n" << r.output;
  EXPECT_NE(r.output.find(words), std::string::npos) << args << "\n" << r.output;
}

const std::string kSmall = " --scene thesis:sphere:5 --size 32x18 --frames 1 --warmup 0";

TEST(Cli, BadFlagValuesAreOneLineUserErrors) {
  expect_user_error("render --backend embree" + kSmall + " --frames 0", "--frames");
  expect_user_error("render --backend embree" + kSmall + " --max-depth 17", "--max-depth");
  expect_user_error("render --backend embree" + kSmall + " --no-such-flag", "no-such-flag");
  expect_user_error("nosuchcommand", "nosuchcommand");
  EXPECT_EQ(run_sdfbench("--help").exit_code, 0);
  EXPECT_EQ(run_sdfbench("render --help").exit_code, 0);
}

TEST(Cli, InfoListsLavapipeAndTheMeshes) {
  const test::CommandResult r = run_sdfbench("info");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("llvmpipe"), std::string::npos) << r.output;
  // The device's limits (lavapipe on Mesa 25: 64-bit timestamps in ns, 128 Mi texels).
  for (const char* limit : {"limits:   subgroup ", ", timestamps 64 bits x 1 ns, texel buffers 134217728 texels, storage buffers "})
    EXPECT_NE(r.output.find(limit), std::string::npos) << limit << "\n" << r.output;
  for (const char* line : {"bunny     4968", "teapot    4032", "monkey     968", "sphere     768"})
    EXPECT_NE(r.output.find(line), std::string::npos) << line << "\n" << r.output;
}

TEST(Cli, RenderWritesImageAndAovs) {
  test::TempDir dir;
  const auto png = dir.path() / "a.png", exr = dir.path() / "a.exr";
  const test::CommandResult r =
      run_sdfbench("render --backend tri-aabb" + kSmall + " --out " + png.string() + " --aov " + exr.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("FPS"), std::string::npos);
  EXPECT_NE(r.output.find("Mrays/s"), std::string::npos);
  EXPECT_GT(std::filesystem::file_size(png), 100u);
  EXPECT_GT(std::filesystem::file_size(exr), 100u);
  // Only the two outputs: no temp files left behind.
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), {}), 2);
}

TEST(Cli, BadDeviceIsAClearError) {
  expect_user_error("render --backend tri-aabb" + kSmall + " --device no-such-gpu", "no Vulkan device matches");
  expect_user_error("render --backend tri-aabb" + kSmall + " --device 99", "no Vulkan device matches");
}

TEST(Cli, UnwritableOutputIsAClearErrorBeforeRendering) {
  expect_user_error("render --backend embree" + kSmall + " --out /nonexistent-dir/a.png", "does not exist");
  expect_user_error("render --backend embree" + kSmall + " --out /proc/a.png", "not writable");
  expect_user_error("render --backend embree" + kSmall + " --out out.unknownformat", "unsupported image format");
}

TEST(Cli, ZeroOrMalformedSizeIsAClearError) {
  for (const char* size : {"0x0", "320x0", "0x180", "-5x10", "320", "axb", "99999x10"})
    expect_user_error(std::string("render --backend embree --scene thesis:sphere:1 --size ") + size, "--size");
}

TEST(Cli, BadSceneAndBackendAreClearErrors) {
  test::TempDir dir;
  const auto broken = dir.write("broken.json", "{ \"meshes\": ");
  expect_user_error("render --backend embree --scene " + broken.string(), "malformed JSON");
  expect_user_error("render --backend embree --scene " + (dir.path() / "missing.json").string(), "does not exist");
  expect_user_error("render --backend embree --scene thesis:cube:10", "unknown mesh");
  expect_user_error("render --backend rasterizer --scene thesis:sphere:1", "unknown backend");
  expect_user_error("render --backend embree --scene thesis:sphere:1 --mode fancy", "--mode");
}

TEST(Cli, CompareAgreesAndFailsOnImpossibleThresholds) {
  const std::string base = "compare --scene thesis:bunny:20 --backends embree,tri-aabb --size 64x36";
  const test::CommandResult ok = run_sdfbench(base);
  EXPECT_EQ(ok.exit_code, 0) << ok.output;
  EXPECT_NE(ok.output.find("tri-aabb"), std::string::npos);
  const test::CommandResult strict = run_sdfbench(base + " --max-depth-error 0 --min-psnr 1000");
  EXPECT_EQ(strict.exit_code, 2) << strict.output;
  EXPECT_NE(strict.output.find("FAIL"), std::string::npos) << strict.output;
}

TEST(Cli, HelpAndMissingArguments) {
  EXPECT_EQ(run_sdfbench("--help").exit_code, 0);
  EXPECT_EQ(run_sdfbench("render --help").exit_code, 0);
  EXPECT_NE(run_sdfbench("render --backend embree").exit_code, 0);  // --scene is required
  EXPECT_NE(run_sdfbench("").exit_code, 0);                          // a command is required
}

}  // namespace
}  // namespace sdfbench
