#include "harness/row_verdict.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>

namespace sdfbench {
namespace {

bool starts_with(std::string_view text, std::string_view prefix) { return text.substr(0, prefix.size()) == prefix; }

// The runner's " (N validation messages)" at the end of a non-ERROR agreement; an ERROR row's
// text is an error message, whatever words it holds.
bool has_validation_messages(std::string_view agreement) {
  constexpr std::string_view tail = " validation messages)";
  if (!agreement.ends_with(tail)) return false;
  agreement.remove_suffix(tail.size());
  size_t digits = 0;
  while (digits < agreement.size() && agreement[agreement.size() - 1 - digits] >= '0' &&
         agreement[agreement.size() - 1 - digits] <= '9')
    ++digits;
  return digits > 0 && agreement.substr(0, agreement.size() - digits).ends_with(" (");
}

constexpr std::array<VerdictMark, 8> kMarks = {{
    {Mark::error, "ERROR", "the configuration failed", true},
    {Mark::disagree, "✗", "images disagree with the reference (the CSV's agreement column says how)", true},
    {Mark::truncated, "✂",
     "lavapipe's loop limit or a traversal's hard bound cut pixels short: image and FPS invalid (docs/limits.md, "
     "\"The loop limit\")",
     true},
    {Mark::validation, "V",
     "the Vulkan validation layers reported warnings or errors (--validate): the figures are not to be trusted", true},
    {Mark::not_reproduced, "≠", "re-rendered images whose agreement figures are not the row's", true},
    {Mark::approximate, "≈",
     "approximate: a sampled field's own hits (--hit field), held to the field's accuracy (depth error p99 within 2 "
     "voxels), not to the exact gate the agreement column reports",
     false},
    {Mark::budget_cut, "†",
     "the time budget cut the run (fewer frames than asked; a single cold frame when only the warm-up fitted)", false},
    {Mark::busy, "‡",
     "timed on a busy machine (load average above 1.5x the cores, CPU steal above 5 % or other processes above 10 %: "
     "the CSV's load columns)",
     false},
}};

// verdict_mark() indexes kMarks by kind.
constexpr bool in_kind_order() {
  for (size_t i = 0; i < kMarks.size(); ++i)
    if (static_cast<size_t>(kMarks[i].kind) != i) return false;
  return true;
}
static_assert(in_kind_order());

}  // namespace

std::span<const VerdictMark> all_verdict_marks() { return kMarks; }

const VerdictMark& verdict_mark(Mark kind) { return kMarks.at(static_cast<size_t>(kind)); }

bool RowVerdict::has(Mark kind) const {
  return std::any_of(marks.begin(), marks.end(), [&](const VerdictMark& m) { return m.kind == kind; });
}
bool RowVerdict::is_error() const { return has(Mark::error); }
bool RowVerdict::is_failure() const {
  return std::any_of(marks.begin(), marks.end(), [](const VerdictMark& m) { return m.failure; });
}
bool RowVerdict::is_caution() const { return !marks.empty() && !is_failure(); }
bool RowVerdict::is_approximate() const { return has(Mark::approximate) && !is_failure(); }

std::string RowVerdict::symbols() const {
  std::string text;
  for (const VerdictMark& m : marks) text.append(text.empty() ? "" : " ").append(m.symbol);
  return text;
}

std::string RowVerdict::reasons() const {
  std::string text;
  for (const VerdictMark& m : marks) {
    text.append(text.empty() ? "" : "; ");
    if (m.kind == Mark::approximate && approximate_voxels) {
      char figure[32];
      std::snprintf(figure, sizeof figure, "%.2f", *approximate_voxels);
      text.append("approximate: field hits, depth error ").append(figure).append(" voxels (p99)");
    } else {
      text.append(m.legend);
    }
  }
  return text;
}

RowVerdict row_verdict(const RowFacts& facts) {
  RowVerdict v;
  auto add = [&](Mark kind) { v.marks.push_back(verdict_mark(kind)); };
  const bool error = starts_with(facts.agreement, "ERROR");
  if (error) add(Mark::error);
  if (starts_with(facts.agreement, "DISAGREE")) {
    // Field hits that stay within the field's accuracy are an approximation; beyond it, or
    // without the figure, the row disagrees like any other.
    const bool within = facts.hit == "field" && facts.depth_p99_voxels && *facts.depth_p99_voxels <= kFieldHitVoxelBound;
    if (within) v.approximate_voxels = facts.depth_p99_voxels;
    else add(Mark::disagree);
  }
  if (starts_with(facts.agreement, "TRUNCATED")) add(Mark::truncated);
  if (!error && has_validation_messages(facts.agreement)) add(Mark::validation);
  if (facts.not_reproduced) add(Mark::not_reproduced);
  if (v.approximate_voxels) add(Mark::approximate);
  if (facts.budget_cut) add(Mark::budget_cut);
  if (facts.busy) add(Mark::busy);
  return v;
}

RowVerdict row_verdict(const CsvTable& table, const std::vector<std::string>& row, bool not_reproduced) {
  auto field = [&](const char* column) -> std::string_view {
    return table.has_column(column) ? std::string_view(row.at(table.column(column))) : std::string_view();
  };
  std::optional<double> voxels;
  if (const std::string_view text = field("depth_p99_voxels"); !text.empty()) {
    double value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error == std::errc() && end == text.data() + text.size() && std::isfinite(value)) voxels = value;
  }
  return row_verdict({field("agreement"), field("budget_cut") == "1", field("busy") == "1", not_reproduced, field("hit"), voxels});
}

std::string verdict_legend(std::span<const VerdictMark> marks) {
  std::string text;
  for (const VerdictMark& m : marks) text.append(text.empty() ? "" : ", ").append(m.symbol).append(" ").append(m.legend);
  return text;
}

}  // namespace sdfbench
