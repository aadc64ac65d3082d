#include "harness/run_options.h"

#include <iostream>

#include "harness/benchmark_json.h"
#include "harness/cli_common.h"
#include "harness/image_store.h"
#include "harness/commands.h"
#include "harness/markdown_report.h"
#include "harness/row_verdict.h"
#include "harness/thesis_tables.h"
#include "util/atomic_file.h"
#include "util/error.h"

namespace sdfbench {

PlanOptions RunOptions::plan() const { return {csv, resume, parse_shard(shard)}; }

void add_run_options(CLI::App& command, RunOptions& o) {
  const std::string method = "Methodology", out = "Output";
  command.add_option("--frames", o.settings.frames, "timed frames per configuration")
      ->capture_default_str()->check(CLI::Range(1u, 100000u))->group(method);
  command.add_option("--warmup", o.settings.warmup, "untimed warm-up frames per configuration")
      ->capture_default_str()->check(CLI::Range(0u, 1000u))->group(method);
  command.add_option("--budget-s", o.settings.budget_s,
                     "time budget per configuration (s): no further frame starts once it would be exceeded; the row says so")
      ->capture_default_str()->check(number_in(0.0, 1e7, true))->group(method);
  command.add_option("--check-size", o.check_size, "resolution of the image-agreement check against the reference")
      ->capture_default_str()->group(method);
  command.add_option("--reference", o.settings.reference, "backend every row's images are compared with")
      ->capture_default_str()->group(method);
  command.add_option("--csv", o.csv, "write one row per measurement (rewritten atomically after every row)")->group(out);
  command.add_option("--markdown", o.markdown, "write the markdown tables at the end")->group(out);
  command.add_option("--json", o.json,
                     "write the rows at the end as Google Benchmark JSON (for libbenchmark-tools' compare.py; "
                     "docs/commands.md)")
      ->group(out);
  command.add_option("--keep-images", o.keep_images,
                     "keep each row's check images in this folder (created if missing): the backend's frame, the "
                     "reference's and their difference map, PNG at --check-size; the CSV names them (for `sdfbench report`)")
      ->group(out);
  command.add_option("--shard", o.shard, "run only the K-th of N slices of the configurations (round robin), e.g. 2/4")
      ->capture_default_str()->group(out);
  command.add_flag("--resume", o.resume, "keep the rows already in --csv and run only the missing configurations")->group(out);
}

void write_markdown(const std::string& path, const CsvTable& rows) {
  if (path.empty()) return;
  const std::string text = markdown_report(rows, ThesisTables::load_default());
  write_file_atomically(path, std::as_bytes(std::span(text.data(), text.size())));
}

void prepare_image_folder(const std::filesystem::path& dir, const char* what) {
  std::error_code ec;
  const std::filesystem::file_status st = std::filesystem::status(dir, ec);
  if (std::filesystem::exists(st) && !std::filesystem::is_directory(st))
    throw Error(std::string(what) + " '" + dir.string() + "' exists and is not a folder");
  if (!std::filesystem::exists(st) && (std::filesystem::create_directories(dir, ec), ec))
    throw Error(std::string(what) + " '" + dir.string() + "': cannot create the folder: " + ec.message());
  check_output_path(dir / "sdfbench-check.png", what);  // writable: fails now, not after the first row
}

int RowTally::exit_status() const { return errors ? kExitRowsFailed : failures ? kExitRowsDisagree : 0; }

RowTally tally_rows(const CsvTable& rows) {
  RowTally tally;
  for (const auto& row : rows.rows) {
    const RowVerdict verdict = row_verdict(rows, row);
    if (verdict.is_error()) ++tally.errors;
    else if (verdict.is_failure()) ++tally.failures;
  }
  return tally;
}

void run_and_report(const std::vector<BenchConfig>& plan, const RunOptions& options, const std::vector<NamedPath>& inputs) {
  const PlanOptions plan_options = options.plan();
  if (!options.markdown.empty()) check_output_path(options.markdown, "--markdown");
  if (!options.json.empty()) check_output_path(options.json, "--json");
  check_distinct_outputs({{"--csv", options.csv}, {"--markdown", options.markdown}, {"--json", options.json},
                          {"--keep-images", options.keep_images},
                          {"--cache", plan.empty() ? std::string() : plan.front().options.cache.path}},
                         inputs);
  RunOptions run = options;  // the kept images' folder, made ready before the first row
  if (!options.keep_images.empty()) {
    std::error_code ec;
    if (std::filesystem::exists(std::filesystem::path(options.keep_images) / ImageStore::kOwnerMarker, ec))
      throw Error("--keep-images '" + options.keep_images +
                  "' is a report's image folder (the next report would remove these images); name another folder");
    prepare_image_folder(options.keep_images, "--keep-images");
    run.settings.keep_images = options.keep_images;
    if (!options.csv.empty()) run.settings.images_base = std::filesystem::path(options.csv).parent_path();
  }
  std::cerr << plan.size() << " configurations";
  if (plan_options.shard.count > 1) std::cerr << " (this is shard " << plan_options.shard.index << "/" << plan_options.shard.count << ")";
  std::cerr << "\n";
  BenchmarkRunner runner(run.settings);
  const CsvTable rows = run_plan(plan, runner, plan_options);
  write_markdown(options.markdown, rows);
  if (!options.json.empty()) {
    const std::string json = benchmark_json(rows);
    write_file_atomically(options.json, std::as_bytes(std::span(json.data(), json.size())));
  }
  std::cout << "\n" << markdown_report(rows, ThesisTables::load_default());
  // The exit status says what the rows say (docs/commands.md, "Tables, sweeps and their CSV").
  const RowTally tally = tally_rows(rows);
  if (tally.errors)
    std::cerr << "sdfbench: " << tally.errors << " of " << rows.rows.size() << " configurations failed (ERROR rows"
              << (options.csv.empty() ? "" : " in '" + options.csv + "'; --resume runs them again") << ")\n";
  else if (tally.failures)
    std::cerr << "sdfbench: " << tally.failures << " of " << rows.rows.size()
              << " configurations disagree with the reference, were cut short or drew Vulkan validation messages "
                 "(DISAGREE, TRUNCATED or validation messages in the agreement column)\n";
  if (const int status = tally.exit_status()) throw CommandFailed{status};
}

}  // namespace sdfbench
