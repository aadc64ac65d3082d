// A row's verdict (harness/row_verdict.h): the marks each kind of agreement text gets, and that
// the markdown, the HTML report and the run's exit status say the same of one row.
#include <gtest/gtest.h>

#include "harness/commands.h"
#include "harness/html_report.h"
#include "harness/markdown_report.h"
#include "harness/measurement.h"
#include "harness/row_verdict.h"
#include "harness/run_options.h"
#include "harness/thesis_tables.h"

namespace sdfbench {
namespace {

std::string symbols_of(const std::string& agreement, bool budget_cut = false, bool busy = false) {
  return row_verdict(RowFacts{agreement, budget_cut, busy}).symbols();
}

TEST(RowVerdict, CleanRowsHaveNoMarks) {
  for (const char* agreement : {"ok", "reference"}) {
    const RowVerdict v = row_verdict(RowFacts{agreement});
    EXPECT_TRUE(v.marks.empty()) << agreement << ": " << v.symbols();
    EXPECT_FALSE(v.is_error() || v.is_failure() || v.is_caution()) << agreement;
  }
}

TEST(RowVerdict, EachAgreementKindGetsItsMark) {
  const RowVerdict disagree = row_verdict(RowFacts{"DISAGREE: hit 98.10 % < 99.50 %"});
  EXPECT_EQ(disagree.symbols(), "✗");
  EXPECT_TRUE(disagree.is_failure());
  EXPECT_FALSE(disagree.is_error());

  const RowVerdict truncated = row_verdict(RowFacts{"TRUNCATED: 200 pixels at the check size"});
  EXPECT_EQ(truncated.symbols(), "✂");
  EXPECT_TRUE(truncated.has(Mark::truncated));
  EXPECT_TRUE(truncated.is_failure());

  const RowVerdict error = row_verdict(RowFacts{"ERROR: vk-rt: device 'x' lacks VK_KHR_ray_tracing_pipeline"});
  EXPECT_EQ(error.symbols(), "ERROR");
  EXPECT_TRUE(error.is_error());
  EXPECT_TRUE(error.is_failure());
  // An error message that happens to name validation messages is an error, not a V.
  EXPECT_EQ(symbols_of("ERROR: Vulkan: VK_EXT_debug_utils is not available for validation messages"), "ERROR");
}

TEST(RowVerdict, ValidationMessagesAreAFailureAfterAnyAgreement) {
  const RowVerdict ok = row_verdict(RowFacts{"ok (3 validation messages)"});
  EXPECT_EQ(ok.symbols(), "V");
  EXPECT_TRUE(ok.is_failure());
  EXPECT_FALSE(ok.is_error());
  EXPECT_EQ(symbols_of("reference (1 validation messages)"), "V");
  EXPECT_EQ(symbols_of("DISAGREE: id 90.00 % < 99.00 % (12 validation messages)"), "✗ V");
  EXPECT_EQ(symbols_of("TRUNCATED: 5 pixels (2 validation messages)"), "✂ V");
}

TEST(RowVerdict, BudgetCutAndBusyAreCautionsUnlessTheRowAlsoFailed) {
  const RowVerdict cut = row_verdict(RowFacts{"ok", true, false});
  EXPECT_EQ(cut.symbols(), "†");
  EXPECT_TRUE(cut.is_caution());
  EXPECT_FALSE(cut.is_failure());

  const RowVerdict busy = row_verdict(RowFacts{"reference", false, true});
  EXPECT_EQ(busy.symbols(), "‡");
  EXPECT_TRUE(busy.is_caution());
  EXPECT_FALSE(busy.is_failure());

  const RowVerdict both = row_verdict(RowFacts{"DISAGREE: hit", true, true});
  EXPECT_EQ(both.symbols(), "✗ † ‡");
  EXPECT_TRUE(both.is_failure());
  EXPECT_FALSE(both.is_caution());
  EXPECT_EQ(both.reasons(), std::string(verdict_mark(Mark::disagree).legend) + "; " +
                                std::string(verdict_mark(Mark::budget_cut).legend) + "; " +
                                std::string(verdict_mark(Mark::busy).legend));
}

TEST(RowVerdict, ARerenderThatDoesNotReproduceTheRowIsAFailure) {
  const RowVerdict v = row_verdict(RowFacts{"ok", false, false, true});
  EXPECT_EQ(v.symbols(), "≠");
  EXPECT_TRUE(v.is_failure());
}

// A sampled field's own hits (--hit field) fail the exact gate by design: within the field's
// accuracy they are an approximation (≈, not red), beyond it or without the figure they disagree.
TEST(RowVerdict, FieldHitsWithinTheFieldsAccuracyAreApproximateNotFailed) {
  const std::string_view gate = "DISAGREE: hit-mask 98.7 % < 99.5 %; depth p99 0.0014 > 0.001";
  const RowVerdict within = row_verdict(RowFacts{gate, false, false, false, "field", 1.34});
  EXPECT_EQ(within.symbols(), "≈");
  EXPECT_TRUE(within.is_approximate());
  EXPECT_TRUE(within.is_caution());
  EXPECT_FALSE(within.is_failure());
  EXPECT_EQ(within.reasons(), "approximate: field hits, depth error 1.34 voxels (p99)");
  EXPECT_EQ(row_verdict(RowFacts{gate, false, false, false, "field", kFieldHitVoxelBound}).symbols(), "≈");

  EXPECT_EQ(row_verdict(RowFacts{gate, false, false, false, "field", kFieldHitVoxelBound * 1.01}).symbols(), "✗")
      << "beyond the field's accuracy";
  EXPECT_EQ(row_verdict(RowFacts{gate, false, false, false, "field", std::nullopt}).symbols(), "✗") << "no figure";
  EXPECT_EQ(row_verdict(RowFacts{gate, false, false, false, "exact", 0.1}).symbols(), "✗") << "exact hits promise the gate";
  EXPECT_EQ(row_verdict(RowFacts{"ok", false, false, false, "field", 0.5}).symbols(), "") << "field hits that pass the gate";
  // Other marks keep their colour: an approximate row with validation messages is red.
  const RowVerdict validated = row_verdict(RowFacts{"DISAGREE: hit (2 validation messages)", true, false, false, "field", 1.0});
  EXPECT_EQ(validated.symbols(), "V ≈ †");
  EXPECT_TRUE(validated.is_failure());
  EXPECT_FALSE(validated.is_approximate());
}

TEST(RowVerdict, ReadsTheCsvColumnsAndOlderCsvsWithoutBusy) {
  CsvTable t;
  t.columns = {"agreement", "budget_cut", "busy"};
  t.rows = {{"ok", "1", "1"}, {"ok", "0", "0"}, {"ok (2 validation messages)", "0", ""}};
  EXPECT_EQ(row_verdict(t, t.rows[0]).symbols(), "† ‡");
  EXPECT_TRUE(row_verdict(t, t.rows[1]).marks.empty());
  EXPECT_EQ(row_verdict(t, t.rows[2]).symbols(), "V");
  EXPECT_EQ(row_verdict(t, t.rows[1], true).symbols(), "≠");

  CsvTable older;
  older.columns = {"agreement", "budget_cut"};
  older.rows = {{"DISAGREE: hit", "1"}};
  EXPECT_EQ(row_verdict(older, older.rows[0]).symbols(), "✗ †");

  CsvTable field;
  field.columns = {"agreement", "hit", "depth_p99_voxels"};
  field.rows = {{"DISAGREE: hit", "field", "1.5"}, {"DISAGREE: hit", "field", "2.5"}, {"DISAGREE: hit", "field", "nan"},
                {"DISAGREE: hit", "field", "1.5x"}, {"DISAGREE: hit", "exact", "1.5"}};
  const std::vector<std::string> expected = {"≈", "✗", "✗", "✗", "✗"};
  for (size_t i = 0; i < field.rows.size(); ++i) EXPECT_EQ(row_verdict(field, field.rows[i]).symbols(), expected[i]) << i;
}

// One mode, one scene: the reference and one vk-rt row whose agreement is `agreement` (or, with
// `field_voxels`, one sdf-global row of field hits with that depth error).
CsvTable two_rows(const std::string& agreement, bool budget_cut = false, std::optional<double> field_voxels = std::nullopt) {
  CsvTable t;
  t.columns = measurement_columns();
  t.source = "rows.csv";
  auto add = [&](const std::string& backend, double fps, const std::string& row_agreement, bool cut) {
    Measurement m;
    m.run_index = t.rows.size();
    m.scene = "thesis:bunny:1";
    m.mesh = "bunny";
    m.objects = 1;
    m.backend = backend;
    m.mode = "whitted";
    m.width = 320;
    m.height = 180;
    m.fps = fps;
    m.agreement = row_agreement;
    m.budget_cut = cut;
    std::vector<std::string> fields = to_csv_fields(m);
    if (field_voxels && backend != "embree") {
      fields[t.column("hit")] = "field";
      fields[t.column("depth_p99_voxels")] = std::to_string(*field_voxels);
    }
    t.rows.push_back(fields);
  };
  add("embree", 300, "reference", false);
  add(field_voxels ? "sdf-global" : "vk-rt", 5, agreement, budget_cut);
  return t;
}

std::string html_of(const CsvTable& t) {
  return html_report({ReportFile{t, std::vector<RowImages>(t.rows.size())}}, {}, ThesisTables::load_default(), "test");
}

TEST(RowVerdictViews, ARowWithValidationMessagesIsMarkedVEverywhere) {
  const CsvTable t = two_rows("ok (3 validation messages)");

  const std::string md = markdown_report(t, ThesisTables::load_default());
  EXPECT_NE(md.find("| bunny | 1 | 300 | 5.00 V |"), std::string::npos) << md;
  EXPECT_NE(md.find("V the Vulkan validation layers reported warnings or errors"), std::string::npos)
      << "the markdown's legend lists V:\n" << md;

  const std::string html = html_of(t);
  EXPECT_NE(html.find("<tr id=\"f0r1\" class=\"bad\">"), std::string::npos) << "the row is red:\n" << html;
  EXPECT_NE(html.find("<tr id=\"f0r0\" class=\"\">"), std::string::npos) << "the reference row is not flagged:\n" << html;
  EXPECT_NE(html.find("<td>5.00 V</td>"), std::string::npos) << html;
  EXPECT_NE(html.find("<li class=\"bad\"><a href=\"#f0r1\">"), std::string::npos) << "listed with the flagged rows:\n" << html;

  EXPECT_EQ(tally_rows(t).failures, 1u);
  EXPECT_EQ(tally_rows(t).exit_status(), kExitRowsDisagree);
}

// The same row in the three views, for each kind of row: its marks in the markdown's and the
// page's FPS cell, the page's colour and the run's exit status.
TEST(RowVerdictViews, MarkdownHtmlAndExitStatusAgreeOnEveryKindOfRow) {
  struct Case {
    std::string agreement;
    bool budget_cut;
    std::string cell, row_class;
    int exit_status;
    std::optional<double> field_voxels = std::nullopt;
  };
  const std::vector<Case> cases = {
      {"ok", false, "5.00", "", 0},
      {"ok", true, "5.00 †", "warn", 0},
      {"DISAGREE: hit 98.10 % < 99.50 %", false, "5.00 ✗", "bad", kExitRowsDisagree},
      {"TRUNCATED: 200 pixels", false, "5.00 ✂", "bad", kExitRowsDisagree},
      {"DISAGREE: hit (2 validation messages)", true, "5.00 ✗ V †", "bad", kExitRowsDisagree},
      {"ERROR: out of device memory", false, "ERROR", "bad", kExitRowsFailed},
      {"DISAGREE: hit 98.10 % < 99.50 %", false, "5.00 ≈", "approx", 0, 1.5},
      {"DISAGREE: hit 98.10 % < 99.50 %", false, "5.00 ✗", "bad", kExitRowsDisagree, 3.0},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.agreement + (c.budget_cut ? ", budget cut" : ""));
    const CsvTable t = two_rows(c.agreement, c.budget_cut, c.field_voxels);
    const std::string md = markdown_report(t, ThesisTables::load_default());
    EXPECT_NE(md.find("| bunny | 1 | 300 | " + c.cell + " |"), std::string::npos) << md;
    const std::string html = html_of(t);
    EXPECT_NE(html.find("<tr id=\"f0r1\" class=\"" + c.row_class + "\">"), std::string::npos) << html;
    EXPECT_NE(html.find("<td>" + c.cell + "</td>"), std::string::npos) << html;
    EXPECT_EQ(tally_rows(t).exit_status(), c.exit_status);
  }
}

}  // namespace
}  // namespace sdfbench
