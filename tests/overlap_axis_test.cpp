// The overlap axis (issue 37): `table --table overlap` and `sweep --overlap` at tiny sizes, the
// rows they write read back (resume, merge, configuration); their errors are among
// TableCommand.BadArgumentsAreClearErrors (harness_test.cpp).
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "harness/csv.h"
#include "harness/measurement.h"
#include "harness/overlap_axis.h"
#include "harness/row_configuration.h"
#include "tests/test_support.h"
#include "util/error.h"

namespace sdfbench {
namespace {

namespace fs = std::filesystem;

std::string text_of(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(OverlapAxis, ScenesKeepTheSpecButItsK) {
  EXPECT_EQ(overlap_scene("bunny", 1000, 4), "overlap:bunny:1000:4");
  EXPECT_EQ(overlap_scene("sphere", 10, 1.5), "overlap:sphere:10:1.5");
  EXPECT_EQ(with_overlap("overlap:teapot:20:3:7", 16), "overlap:teapot:20:16:7");
  EXPECT_EQ(with_overlap("overlap:teapot:20:3", 2.25), "overlap:teapot:20:2.25");
  EXPECT_EQ(asked_overlap("overlap:teapot:20:3:7"), "3");
  EXPECT_EQ(asked_overlap("thesis:bunny:10"), "");
  EXPECT_EQ(overlap_family("overlap:teapot:20:3:7"), "overlap:teapot:20:<k>:7");
  EXPECT_EQ(overlap_family("thesis:bunny:10"), "thesis:bunny:10");
  EXPECT_THROW(with_overlap("thesis:bunny:10", 2), Error);
}

const std::string kRun = " --size 32x18 --check-size 32x18 --frames 1 --warmup 0";
const std::string kOverlapTable = "table --table overlap --meshes sphere --objects 6 --overlap 1,8 --backends bvh,sdf-global --cells-per-extent 8" + kRun;

TEST(OverlapAxis, TableRunsEveryBackendOnEachKAndItsRowsReadBack) {
  test::TempDir dir;
  const fs::path csv = dir.path() / "overlap.csv", md = dir.path() / "overlap.md";
  const test::CommandResult r = test::run_sdfbench(kOverlapTable + " --csv " + csv.string() + " --markdown " + md.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const CsvTable table = read_csv(csv);
  ASSERT_EQ(table.rows.size(), 4u);
  const char* scenes[] = {"overlap:sphere:6:1", "overlap:sphere:6:1", "overlap:sphere:6:8", "overlap:sphere:6:8"};
  const char* backends[] = {"bvh", "sdf-global", "bvh", "sdf-global"};
  for (size_t i = 0; i < 4; ++i) {
    const auto& row = table.rows[i];
    EXPECT_EQ(row[table.column("table")], "overlap");
    EXPECT_EQ(row[table.column("scene")], scenes[i]);
    EXPECT_EQ(row[table.column("backend")], backends[i]);
    EXPECT_EQ(row[table.column("mode")], "primary");
    EXPECT_EQ(row[table.column("agreement")], "ok") << row[table.column("agreement")];
    EXPECT_FALSE(row[table.column("overlap")].empty());
    // the configuration the row records is the one that ran (report --render-missing renders it)
    const RowConfiguration read = row_configuration(table, i);
    EXPECT_EQ(read.config.scene, scenes[i]);
    EXPECT_EQ(read.config.table, "overlap");
  }
  EXPECT_GT(std::stod(table.rows[2][table.column("overlap")]), 2 * std::stod(table.rows[0][table.column("overlap")]));

  const std::string text = text_of(md);
  EXPECT_NE(text.find("### Overlap: sphere, 6 objects, primary mode (32x18): Mrays/s"), std::string::npos) << text;
  EXPECT_NE(text.find("| k | overlap | bvh | sdf-global | sdf-global / bvh |"), std::string::npos) << text;
  EXPECT_NE(text.find("\n| 1 | "), std::string::npos) << text;
  EXPECT_NE(text.find("\n| 8 | "), std::string::npos) << text;
  EXPECT_EQ(text.find("### Every backend"), std::string::npos) << "overlap rows are not the thesis' object axis";

  // --resume finds every configuration done; merge takes the file as one run.
  const test::CommandResult resumed = test::run_sdfbench(kOverlapTable + " --csv " + csv.string() + " --resume");
  EXPECT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("resume: 4 configuration(s) already in"), std::string::npos) << resumed.output;
  EXPECT_EQ(read_csv(csv).rows, table.rows);
  const fs::path merged = dir.path() / "merged.csv";
  const test::CommandResult m = test::run_sdfbench("merge " + csv.string() + " --csv " + merged.string());
  EXPECT_EQ(m.exit_code, 0) << m.output;
  EXPECT_EQ(read_csv(merged).rows, table.rows);
  // Another list of k is another run.
  const test::CommandResult other = test::run_sdfbench(
      "table --table overlap --meshes sphere --objects 6 --overlap 1,4 --backends bvh,sdf-global --cells-per-extent 8" + kRun + " --csv " + csv.string() +
      " --resume");
  EXPECT_EQ(other.exit_code, 1) << other.output;
  EXPECT_NE(other.output.find("overlap:sphere:6:4"), std::string::npos) << other.output;
}

TEST(OverlapAxis, SweepVariesTheScenesK) {
  test::TempDir dir;
  const fs::path csv = dir.path() / "sweep.csv";
  const test::CommandResult r = test::run_sdfbench("sweep --scene overlap:sphere:6:2:7 --backend sdf-global --overlap 1,8 "
                                                   "--cells-per-extent 8 --sdf-format f32,f16" + kRun + " --csv " + csv.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const CsvTable table = read_csv(csv);
  ASSERT_EQ(table.rows.size(), 4u);
  const char* scenes[] = {"overlap:sphere:6:1:7", "overlap:sphere:6:1:7", "overlap:sphere:6:8:7", "overlap:sphere:6:8:7"};
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(table.rows[i][table.column("scene")], scenes[i]);
    EXPECT_EQ(table.rows[i][table.column("table")], "sweep");
    EXPECT_EQ(row_configuration(table, i).config.scene, scenes[i]);
  }
  // One sweep table over k and the format, not one per scene.
  EXPECT_NE(r.output.find("### Sweep: overlap:sphere:6:<k>:7, sdf-global, primary (32x18)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("| k | overlap | sdf_format |"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("### Sweep: overlap:sphere:6:1:7"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace sdfbench
