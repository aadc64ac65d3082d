#pragma once
// The verdict of a result row: which marks it gets (ERROR, ✗, ✂, V, ≠, ≈, †, ‡), read from its
// agreement text, hit mode, depth error, budget_cut and busy columns. The one place that parses a row's verdict, so
// that the markdown, the HTML report, the exit status and --resume say the same of each row.
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "harness/csv.h"

namespace sdfbench {

// In the order a row lists its marks: the failures, then the cautions.
// ≈ (approximate) is a sampled field's own hits (--hit field): the exact gate still measures the
// row and says DISAGREE, but the field promises only its voxel's accuracy, which the row holds.
enum class Mark { error, disagree, truncated, validation, not_reproduced, approximate, budget_cut, busy };

// How far (p99, in voxels of the row's field) field hits may lie from the exact surface and still
// be an approximation rather than a disagreement: trilinear reconstruction's error, two voxels.
inline constexpr double kFieldHitVoxelBound = 2.0;

struct VerdictMark {
  Mark kind;
  std::string_view symbol;  // as the markdown and the report print it
  std::string_view legend;  // what it means: the legends, and a flagged row's reasons
  bool failure;             // red: the row failed what it promised (its figures are not valid); else a caution (yellow)
};

const VerdictMark& verdict_mark(Mark kind);
std::span<const VerdictMark> all_verdict_marks();

// What the row says of itself; `not_reproduced` is the report's re-render (≠), no column.
struct RowFacts {
  std::string_view agreement;  // "ok", "reference", "DISAGREE: ...", "TRUNCATED: ..." or "ERROR: ...", all
                               // but ERROR possibly followed by " (N validation messages)"
  bool budget_cut = false, busy = false, not_reproduced = false;
  std::string_view hit;                         // the hit column: "field" is a sampled field's own hits
  std::optional<double> depth_p99_voxels;       // their depth error, in voxels of the field
};

struct RowVerdict {
  std::vector<VerdictMark> marks;  // in the order of Mark
  std::optional<double> approximate_voxels;  // with ≈: the row's depth error p99 in voxels

  bool has(Mark kind) const;
  bool is_error() const;    // the configuration failed: --resume runs it again, the run exits 4
  bool is_failure() const;  // any red mark, ERROR included: the run exits 2 (4 when an ERROR row)
  bool is_caution() const;  // marked, but only with yellow marks (≈ among them)
  bool is_approximate() const;  // ≈ and no red mark: listed apart from failures
  std::string symbols() const;  // "✗ V": the marks for a table cell, empty when none
  std::string reasons() const;  // the marks' legends, "; " between them (≈ with the row's depth error)
};

RowVerdict row_verdict(const RowFacts& facts);
// `row`, one of `table`'s rows; a CSV from before the busy column reads as not busy.
RowVerdict row_verdict(const CsvTable& table, const std::vector<std::string>& row, bool not_reproduced = false);

// "ERROR the configuration failed, ✗ images disagree ...": each of `marks` with its legend.
std::string verdict_legend(std::span<const VerdictMark> marks);

}  // namespace sdfbench
