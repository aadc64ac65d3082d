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
}

// One mode, one scene: the reference and one vk-rt row whose agreement is `agreement`.
CsvTable two_rows(const std::string& agreement, bool budget_cut = false) {
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
    t.rows.push_back(to_csv_fields(m));
  };
  add("embree", 300, "reference", false);
  add("vk-rt", 5, agreement, budget_cut);
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
  };
  const std::vector<Case> cases = {
      {"ok", false, "5.00", "", 0},
      {"ok", true, "5.00 †", "warn", 0},
      {"DISAGREE: hit 98.10 % < 99.50 %", false, "5.00 ✗", "bad", kExitRowsDisagree},
      {"TRUNCATED: 200 pixels", false, "5.00 ✂", "bad", kExitRowsDisagree},
      {"DISAGREE: hit (2 validation messages)", true, "5.00 ✗ V †", "bad", kExitRowsDisagree},
      {"ERROR: out of device memory", false, "ERROR", "bad", kExitRowsFailed},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.agreement + (c.budget_cut ? ", budget cut" : ""));
    const CsvTable t = two_rows(c.agreement, c.budget_cut);
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
