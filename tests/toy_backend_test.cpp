// Issue 36's acceptance: a backend registered from outside sdfbench (tests/toy_backend/, one
// parameter of its own) is a first-class backend without any edit in harness/ or the registry:
// it renders, shows in help and in `backends --json`, is a sweep axis, writes and reads back its
// CSV column, and appears in `report`.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "harness/cli_main.h"
#include "harness/csv.h"
#include "harness/row_configuration.h"
#include "tests/test_support.h"
#include "tests/toy_backend/toy_renderer.h"

namespace sdfbench {
namespace {

struct CliRun {
  int code = -1;
  std::string out, err;
};

// The sdfbench command line in this process, where the toy is registered.
CliRun sdfbench(std::vector<std::string> args) {
  static const bool registered = [] {
    register_backend(toy::toy_backend());
    return true;
  }();
  (void)registered;
  args.insert(args.begin(), "sdfbench");
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  CliRun run;
  run.code = run_sdfbench(static_cast<int>(argv.size()), argv.data());
  run.out = testing::internal::GetCapturedStdout();
  run.err = testing::internal::GetCapturedStderr();
  return run;
}

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(ToyBackend, RendersShowsInHelpAndBackends) {
  test::TempDir dir;
  const CliRun render = sdfbench({"render", "--scene", "thesis:sphere:3", "--backend", "toy", "--toy-order", "reverse", "--size",
                               "40x24", "--frames", "1", "--warmup", "0", "--out", (dir.path() / "toy.png").string()});
  ASSERT_EQ(render.code, 0) << render.err;
  EXPECT_NE(render.out.find("params   toy_order=reverse"), std::string::npos) << render.out;
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "toy.png"));

  const CliRun help = sdfbench({"render", "--help"});
  EXPECT_NE(help.out.find("--toy-order"), std::string::npos);
  EXPECT_NE(help.out.find("toy (`sdfbench backends`"), std::string::npos) << "the --backend help lists it";
  const CliRun listed = sdfbench({"backends", "--json"});
  EXPECT_NE(listed.out.find("\"name\": \"toy\""), std::string::npos);
  EXPECT_NE(listed.out.find("\"flag\": \"--toy-order\""), std::string::npos);

  // Its parameter is refused where no backend of the run takes it, and its values are checked.
  const CliRun misplaced = sdfbench({"render", "--scene", "thesis:sphere:1", "--backend", "embree", "--toy-order", "reverse"});
  EXPECT_EQ(misplaced.code, 1);
  EXPECT_NE(misplaced.err.find("--toy-order is a parameter of toy; no backend of this run (embree) takes it"), std::string::npos)
      << misplaced.err;
  const CliRun bad = sdfbench({"render", "--scene", "thesis:sphere:1", "--backend", "toy", "--toy-order", "sideways"});
  EXPECT_EQ(bad.code, 1);
  EXPECT_NE(bad.err.find("expected forward or reverse, got 'sideways'"), std::string::npos) << bad.err;
}

TEST(ToyBackend, IsASweepAxisWithItsOwnCsvColumnReadBackAndReported) {
  test::TempDir dir;
  const std::string csv = (dir.path() / "toy.csv").string();
  const CliRun sweep = sdfbench({"sweep", "--scene", "thesis:sphere:3", "--backend", "toy", "--toy-order", "forward,reverse", "--size",
                              "40x24", "--check-size", "40x24", "--frames", "1", "--warmup", "0", "--csv", csv});
  ASSERT_EQ(sweep.code, 0) << sweep.err;
  const CsvTable table = read_csv(csv);
  ASSERT_TRUE(table.has_column("toy_order"));
  ASSERT_EQ(table.rows.size(), 2u);
  EXPECT_EQ(table.rows[0][table.column("toy_order")], "forward");
  EXPECT_EQ(table.rows[1][table.column("toy_order")], "reverse");
  for (const auto& row : table.rows) EXPECT_EQ(row[table.column("agreement")], "ok") << "the toy draws what Embree draws";
  EXPECT_EQ(row_configuration(table, 1).config.options.params.text("toy_order"), "reverse");

  const std::string page = (dir.path() / "report.html").string();
  const CliRun report = sdfbench({"report", csv, "--render-missing", "--out", page});
  ASSERT_EQ(report.code, 0) << report.err;
  const std::string html = read_file(page);
  EXPECT_NE(html.find("toy_order"), std::string::npos);
  EXPECT_NE(html.find("reverse"), std::string::npos);
  EXPECT_EQ(html.find("re-rendered images are not the row's"), std::string::npos) << "both rows reproduce their figures";
  EXPECT_EQ(read_csv((dir.path() / "report_files" / "rendered.csv").string()).rows.size(), 2u) << "both rows were rendered again";
}

}  // namespace
}  // namespace sdfbench
