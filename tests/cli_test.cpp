// The command line, as a user meets it: clear errors and non-zero exits, never a crash.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>

#include <gtest/gtest.h>

#include "renderers/backend_registry.h"
#include "tests/test_support.h"
#include "util/error.h"

namespace sdfbench {

std::vector<BackendInfo> builtin_backends();  // renderers/builtin_backends.cpp

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

// A parameter is parsed and checked once, by its declaration, to a typed value: resolve_params
// gives every parameter a backend owns as its declaration types it (defaults included), a flag's
// typed value is checked against the backend's own declaration without being parsed again, and
// reading one not resolved, not declared or of another kind is an internal error.
TEST(Cli, ParametersAreTypedOnceByTheirDeclaration) {
  for (const BackendInfo& backend : backends()) {  // every default is a value its declaration takes, spelled canonically
    const BackendParams resolved = resolve_params(backend, BackendParams{});
    for (const ParamSpec& spec : backend.params) {
      ASSERT_TRUE(resolved.typed(spec.name)) << backend.name << ": " << spec.name;
      EXPECT_EQ(resolved.text(spec.name), spec.default_value) << backend.name << ": " << spec.name;
    }
  }
  const std::string global_name = "sdf-global";  // a named string: GCC 14 flags a reference from a temporary's lookup
  const BackendInfo& global = backend_info(global_name);
  BackendParams given;
  given.set("global_voxel", "0.50");  // as text (a test's, a CSV row's): parsed by resolve_params
  given.set("brick_band", "008");
  EXPECT_THROW(given.real("global_voxel"), InternalError);  // not resolved yet
  BackendParams resolved = resolve_params(global, given);
  EXPECT_EQ(resolved.text("global_voxel"), "0.5");
  EXPECT_EQ(resolved.real("global_voxel"), 0.5);
  EXPECT_FALSE(resolved.is_word("global_voxel"));
  EXPECT_EQ(resolved.integer("brick_band"), 8);
  EXPECT_EQ(resolved.text("brick_band"), "8");
  EXPECT_EQ(resolved.text("hit"), "exact");
  EXPECT_FALSE(resolved.flag("storage_tables"));
  EXPECT_THROW(resolved.integer("global_voxel"), InternalError);  // another kind
  EXPECT_THROW(resolved.real("hash_cell"), InternalError);       // sdf-global does not declare it
  given.set("global_voxel", "auto");
  resolved = resolve_params(global, given);
  EXPECT_TRUE(resolved.is_word("global_voxel"));
  EXPECT_THROW(resolved.real("global_voxel"), InternalError);
  // A value typed by the catalogue's declaration (a flag's): every backend's choices, each backend its own.
  std::string why;
  const std::optional<TypedParam> field = parse_param(catalogue_spec("hit"), "field", why);
  ASSERT_TRUE(field) << why;
  BackendParams flagged;
  flagged.set("hit", *field);
  EXPECT_EQ(resolve_params(global, flagged).text("hit"), "field");
  EXPECT_THROW(resolve_params(backend_info("sdf-octree"), flagged), Error);
  EXPECT_FALSE(parse_param(catalogue_spec("hash_cell"), "1e-7", why));
  EXPECT_EQ(why, "expected a number in [1e-06, 1e+09], got '1e-7'");
  // Equal configurations: the canonical texts, typed or not.
  BackendParams as_text;
  as_text.set("hit", "field");
  EXPECT_EQ(as_text, flagged);
}

// docs/commands.md's CSV table lists every backend's parameters (its "every backend's parameters
// (...)" row): the built-in backends' parameters of the registry, in its (the CSV's) order, and no
// other.
TEST(Cli, DocsListEveryParameter) {
  const std::filesystem::path doc = std::filesystem::path(SDFBENCH_DATA_DIR).parent_path() / "docs" / "commands.md";
  std::ifstream in(doc);
  ASSERT_TRUE(in) << doc;
  const std::string row = "| every backend's parameters (", tail = ", and those of any backend registered at run time)";
  std::vector<std::string> listed;
  bool found = false;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(row, 0) != 0) continue;
    const size_t end = line.find(tail);
    ASSERT_NE(end, std::string::npos) << doc << ": the parameters' row does not end its list with \"" << tail << "\"";
    const std::string list = line.substr(row.size(), end - row.size());
    for (size_t begin = 0; begin <= list.size();) {
      const size_t comma = std::min(list.find(", ", begin), list.size());
      listed.push_back(list.substr(begin, comma - begin));
      begin = comma + 2;
    }
    found = true;
  }
  ASSERT_TRUE(found) << doc << ": no row \"" << row << "...\"";
  std::set<std::string> builtin;  // a backend a test registers (the toy's) is not in the doc
  for (const BackendInfo& b : builtin_backends())
    for (const ParamSpec& spec : b.params) builtin.insert(spec.name);
  std::vector<std::string> declared;
  for (const ParamSpec& spec : param_catalogue())
    if (builtin.count(spec.name)) declared.push_back(spec.name);
  for (const std::string& name : declared)
    EXPECT_NE(std::find(listed.begin(), listed.end(), name), listed.end())
        << doc << ": parameter " << name << " (" << flag_of(catalogue_spec(name)) << ", `sdfbench backends`) is not listed";
  for (const std::string& name : listed)
    EXPECT_TRUE(builtin.count(name)) << doc << ": lists '" << name << "', which no backend declares";
  EXPECT_EQ(listed, declared) << doc << ": the parameters are not listed in the registry's (the CSV's) order";
}

}  // namespace
}  // namespace sdfbench
