#pragma once
// Options shared by `table` and `sweep`: methodology (frames, warm-up, budget, check size),
// outputs (CSV, markdown) and scale-out (shard, resume).
#include <string>

#include <CLI/CLI.hpp>

#include "harness/benchmark_plan.h"
#include "harness/benchmark_runner.h"
#include "harness/output_paths.h"

namespace sdfbench {

struct RunOptions {
  BenchSettings settings;
  std::string check_size = "320x180", shard = "1/1", csv, markdown, json, keep_images;
  bool resume = false;
  PlanOptions plan() const;  // parses --shard
};

void add_run_options(CLI::App& command, RunOptions& options);

// Writes the markdown report of `rows` (with the thesis' values) atomically, if a path was given.
void write_markdown(const std::string& path, const CsvTable& rows);

// Makes `dir` a writable folder for kept images (created with its parents if missing); throws
// Error naming `what` when something else is in its place or it cannot be written.
void prepare_image_folder(const std::filesystem::path& dir, const char* what);

// What a run's rows say (harness/row_verdict.h): ERROR rows, and rows that failed otherwise
// (✗ disagree, ✂ truncated, V validation messages).
struct RowTally {
  size_t errors = 0, failures = 0;
  int exit_status() const;  // kExitRowsFailed when any ERROR row, else kExitRowsDisagree when any failure, else 0
};
RowTally tally_rows(const CsvTable& rows);

// Runs `plan` as `options` say (shard, resume, CSV), then writes and prints the markdown report.
// The outputs (--csv, --markdown, --cache) are checked first against each other and `inputs`
// (the files the plan's scenes are read from). Throws CommandFailed with the rows' exit status
// when some failed (RowTally).
void run_and_report(const std::vector<BenchConfig>& plan, const RunOptions& options, const std::vector<NamedPath>& inputs);

}  // namespace sdfbench
