// "Which structure wins where" (harness/structure_winners.h) and the report's first section:
// groups are one run's rows of one scene, mode and size; each kind's fastest row that did not
// fail competes; approximations (field hits) are shown but never win.
#include <gtest/gtest.h>

#include <algorithm>

#include "harness/html_report.h"
#include "harness/measurement.h"
#include "harness/structure_winners.h"
#include "harness/thesis_tables.h"

namespace sdfbench {
namespace {

struct RowSpec {
  std::string scene, backend, hit;
  double mrays;
  std::string agreement = "ok";
  std::optional<double> voxels = std::nullopt;
};

CsvTable rows_of(const std::vector<RowSpec>& specs, const std::string& source = "run.csv") {
  CsvTable t;
  t.columns = measurement_columns();
  t.source = source;
  for (const RowSpec& s : specs) {
    Measurement m;
    m.run_index = t.rows.size();
    m.scene = s.scene;
    m.backend = s.backend;
    m.mode = "primary";
    m.width = 320;
    m.height = 180;
    m.mrays_per_s = s.mrays;
    m.fps = s.mrays;
    m.agreement = s.backend == "embree" ? "reference" : s.agreement;
    std::vector<std::string> fields = to_csv_fields(m);
    fields[t.column("hit")] = s.hit;
    if (s.voxels) fields[t.column("depth_p99_voxels")] = std::to_string(*s.voxels);
    t.rows.push_back(fields);
  }
  return t;
}

RowVerdict plain_verdict(const std::vector<const CsvTable*>& files, size_t f, size_t r) {
  return row_verdict(*files[f], files[f]->rows[r]);
}

TEST(StructureWinners, EachKindsFastestPassingRowAndTheWinner) {
  const CsvTable t = rows_of({
      {"overlap:bunny:1000:50", "embree", "", 10},
      {"overlap:bunny:1000:50", "bvh", "", 2},
      {"overlap:bunny:1000:50", "vk-rt", "", 1.5},
      {"overlap:bunny:1000:50", "sdf-octree", "exact", 1},
      {"overlap:bunny:1000:50", "sdf-global", "exact", 3},                       // the Vulkan device's fastest
      {"overlap:bunny:1000:50", "sdf-hash", "exact", 50, "DISAGREE: id 90 %"},  // failed: left out, counted
      {"overlap:bunny:1000:50", "sdf-bricks", "field", 20, "DISAGREE: depth", 1.2},  // ≈: its own kind, no winner
      {"overlap:bunny:1000:50", "sdf-cpu", "exact", 100},                       // the reference tracer: no contender
      {"thesis:bunny:1", "bvh", "", 4},
      {"thesis:bunny:1", "sdf-global", "exact", 5},
  });
  const std::vector<const CsvTable*> files = {&t};
  const StructureWinners w = structure_winners(files, [&](size_t f, size_t r) { return plain_verdict(files, f, r); });
  ASSERT_EQ(w.groups.size(), 2u);
  const auto kind = [&](const std::string& name) {
    return static_cast<size_t>(std::find(w.kinds.begin(), w.kinds.end(), name) - w.kinds.begin());
  };
  ASSERT_LT(kind("SDF, field hits (≈)"), w.kinds.size());
  const WinnerGroup& dense = w.groups[0];
  EXPECT_EQ(dense.scene, "overlap:bunny:1000:50");
  EXPECT_EQ(dense.failed, 1u);
  EXPECT_EQ(dense.best[kind("SDF, exact hits")], 4u) << "sdf-global, the fastest SDF row that agreed";
  EXPECT_EQ(dense.best[kind("SDF, field hits (≈)")], 6u);
  EXPECT_EQ(dense.best[kind("compute BVH")], 1u);
  EXPECT_EQ(dense.winner, kind("Embree (CPU)"));
  EXPECT_EQ(dense.vulkan_winner, kind("SDF, exact hits"));
  const WinnerGroup& single = w.groups[1];
  EXPECT_EQ(single.winner, kind("SDF, exact hits"));
  EXPECT_FALSE(single.best[kind("Embree (CPU)")].has_value());
  EXPECT_EQ(competing_kind("sdf-cpu", "exact"), "");
  EXPECT_EQ(competing_kind("no-such-backend", ""), "");
  EXPECT_EQ(competing_kind("sdf-bricks", "thesis"), "SDF, thesis' hits");
}

TEST(StructureWinners, RunsAreNeverMixed) {
  const CsvTable a = rows_of({{"thesis:bunny:1000", "bvh", "", 2}, {"thesis:bunny:1000", "sdf-global", "exact", 1}}, "a.csv");
  const CsvTable b = rows_of({{"thesis:bunny:1000", "bvh", "", 1}, {"thesis:bunny:1000", "sdf-global", "exact", 3}}, "b.csv");
  const std::vector<const CsvTable*> files = {&a, &b};
  const StructureWinners w = structure_winners(files, [&](size_t f, size_t r) { return plain_verdict(files, f, r); });
  ASSERT_EQ(w.groups.size(), 2u) << "the same scene in two runs is two groups";
  EXPECT_EQ(w.kinds[*w.groups[0].winner], "compute BVH");
  EXPECT_EQ(w.kinds[*w.groups[1].winner], "SDF, exact hits");

  CsvTable merged = a;  // `merge --several-runs` (one sweep per backend): one file, set side by side
  for (auto row : b.rows) {
    row[b.column("run_id")] = "second-run";
    merged.rows.push_back(row);
  }
  const std::vector<const CsvTable*> one = {&merged};
  const StructureWinners joined = structure_winners(one, [&](size_t f, size_t r) { return plain_verdict(one, f, r); });
  ASSERT_EQ(joined.groups.size(), 1u);
  EXPECT_EQ(joined.kinds[*joined.groups[0].winner], "SDF, exact hits");
}

TEST(StructureWinners, TheReportOpensWithTheAnswerAndListsApproximationsApart) {
  const CsvTable t = rows_of({
      {"thesis:bunny:1000", "embree", "", 10},
      {"thesis:bunny:1000", "bvh", "", 2},
      {"thesis:bunny:1000", "sdf-global", "exact", 1, "DISAGREE: id 90 %"},
      {"thesis:bunny:1000", "sdf-bricks", "field", 4, "DISAGREE: depth", 1.2},
  });
  const std::string html =
      html_report({ReportFile{t, std::vector<RowImages>(t.rows.size())}}, {}, ThesisTables::load_default(), "test");
  const size_t wins = html.find("<h2 id=\"wins\">Which structure wins where</h2>");
  const size_t flagged = html.find("<h2 id=\"flagged\">");
  const size_t rows = html.find("<h2 id=\"file0\">");
  ASSERT_NE(wins, std::string::npos) << html;
  EXPECT_LT(wins, flagged);
  EXPECT_LT(flagged, rows);
  const std::string section = html.substr(wins, flagged - wins);
  EXPECT_NE(section.find("<b>embree</b></a> 10.000 Mrays/s<br>winner, 5.00x the next"), std::string::npos) << section;
  EXPECT_NE(section.find("bvh</a> 2.000 Mrays/s<br>0.20x the winner; fastest on the Vulkan device"), std::string::npos) << section;
  EXPECT_NE(section.find("1 failed row(s) left out"), std::string::npos) << section;
  EXPECT_NE(section.find("sdf-bricks</a> 4.000 Mrays/s ≈<br>0.40x the winner"), std::string::npos) << section;
  EXPECT_EQ(section.find("sdf-global</a>"), std::string::npos) << "a failed row does not compete";
  const std::string lists = html.substr(flagged, rows - flagged);
  const size_t failed = lists.find("Failed what they promised (1)"), approx = lists.find("Approximations: field hits (1)");
  ASSERT_NE(failed, std::string::npos) << lists;
  ASSERT_NE(approx, std::string::npos) << lists;
  EXPECT_NE(lists.find("<li class=\"bad\"><a href=\"#f0r2\">"), std::string::npos) << lists;
  EXPECT_GT(lists.find("<li class=\"approx\"><a href=\"#f0r3\">"), approx) << "the field row under approximations:\n" << lists;
  EXPECT_NE(lists.find("approximate: field hits, depth error 1.20 voxels (p99)"), std::string::npos) << lists;
}

}  // namespace
}  // namespace sdfbench
