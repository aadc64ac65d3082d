// table/sweep --json: the rows as Google Benchmark JSON, read by Debian's libbenchmark-tools
// compare.py (two small runs compared row by row), with the fields and counters its docs name.
#include <fstream>
#include <set>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/test_support.h"

namespace sdfbench {
namespace {

nlohmann::json read_json(const std::filesystem::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

TEST(BenchmarkJson, TwoRunsCompareWithGoogleBenchmarksTools) {
  const test::TempDir dir;
  const std::string args = "table --table 6.1 --meshes sphere --objects 1,10 --backends embree,bvh --size 16x9 "
                           "--check-size 16x9 --frames 2 --warmup 0";
  for (const char* run : {"a", "b"}) {
    const test::CommandResult r = test::run_sdfbench(args + " --json " + (dir.path() / run).string() + ".json");
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  const nlohmann::json a = read_json(dir.path() / "a.json");
  EXPECT_FALSE(a["context"]["sdfbench_device"].get<std::string>().empty());
  EXPECT_FALSE(a["context"]["sdfbench_commit"].get<std::string>().empty());
  ASSERT_EQ(a["benchmarks"].size(), 4u);  // 2 object counts x 2 backends
  std::set<std::string> names;
  for (const nlohmann::json& b : a["benchmarks"]) {
    names.insert(b["name"].get<std::string>());
    EXPECT_EQ(b["time_unit"], "ms");
    EXPECT_EQ(b["run_type"], "iteration");
    EXPECT_GT(b["real_time"].get<double>(), 0.0);
    EXPECT_EQ(b["iterations"], 2);
    EXPECT_GT(b["mrays_per_s"].get<double>(), 0.0);
    EXPECT_EQ(b["agreement"].get<std::string>() == "reference" || b["agreement"].get<std::string>() == "ok", true) << b;
  }
  EXPECT_EQ(names.size(), 4u) << "every row gets a name of its own";
  EXPECT_EQ(names.count("thesis:sphere:10/bvh/whitted/16x9"), 1u) << a["benchmarks"];

  const test::CommandResult compare = test::run_command("/usr/bin/python3 /usr/share/benchmark/compare.py benchmarks " +
                                                        (dir.path() / "a.json").string() + " " +
                                                        (dir.path() / "b.json").string());
  ASSERT_EQ(compare.exit_code, 0) << compare.output;
  EXPECT_NE(compare.output.find("thesis:sphere:10/bvh/whitted/16x9"), std::string::npos) << compare.output;
  EXPECT_NE(compare.output.find("OVERALL_GEOMEAN"), std::string::npos) << compare.output;
}

TEST(BenchmarkJson, IsAnOutputLikeTheOthers) {
  const test::TempDir dir;
  const std::string csv = (dir.path() / "rows.csv").string();
  const test::CommandResult same = test::run_sdfbench("table --table 6.1 --meshes sphere --objects 1 --backends embree "
                                                      "--size 16x9 --csv " + csv + " --json " + csv);
  EXPECT_EQ(same.exit_code, 1) << same.output;
  EXPECT_NE(same.output.find("--json"), std::string::npos) << same.output;
}

}  // namespace
}  // namespace sdfbench
