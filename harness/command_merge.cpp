// `sdfbench merge`: join the CSVs of one run's shards into one, checking that they have the
// same columns and run id, valid run indices, and do not measure a configuration twice.
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <map>

#include "harness/commands.h"
#include "harness/csv.h"
#include "harness/measurement.h"
#include "harness/output_paths.h"
#include "harness/run_options.h"
#include "util/atomic_file.h"
#include "util/error.h"

namespace sdfbench {
namespace {

struct MergeArgs {
  std::vector<std::string> inputs;
  std::string csv, markdown;
  bool several_runs = false;  // --several-runs: files of different runs, one after the other
};

// The rows of one run only: a shard file left from an earlier run with other settings (same
// file name, same shard count) must not slip into the merge. CSVs from before run_id have none.
void check_same_run(const CsvTable& t, const CsvTable& first) {
  if (!t.has_column("run_id") || t.rows.empty() || first.rows.empty()) return;
  const size_t column = t.column("run_id");
  for (const auto& row : t.rows)
    if (row[column] != first.rows.front()[column])
      throw Error("'" + t.source + "' is not from the run of '" + first.source + "' (run_id '" + row[column] +
                  "' vs '" + first.rows.front()[column] + "'): " + run_difference(first, t) +
                  "; merge the shards of one run (a shard folder may hold files of an earlier run)");
}

// A kept image's path is relative to its CSV's folder (--keep-images): rebased onto the merged
// CSV's folder, so that the merged file names the same images (and `report` finds them).
void rebase_image_paths(CsvTable& t, const std::filesystem::path& from_csv, const std::filesystem::path& to_csv) {
  namespace fs = std::filesystem;
  const fs::path from = fs::weakly_canonical(fs::absolute(from_csv)).parent_path();
  const fs::path to = fs::weakly_canonical(fs::absolute(to_csv)).parent_path();
  if (from == to) return;
  for (const char* name : {"frame_image", "reference_image", "diff_image"}) {
    if (!t.has_column(name)) continue;
    const size_t column = t.column(name);
    for (auto& row : t.rows) {
      std::string& value = row[column];
      if (value.empty() || fs::path(value).is_absolute()) continue;  // an absolute path: report refuses it, named
      value = (from / value).lexically_normal().lexically_relative(to).string();
    }
  }
}

void run_merge(const MergeArgs& args) {
  check_output_path(args.csv, "--csv");
  if (!args.markdown.empty()) check_output_path(args.markdown, "--markdown");
  std::vector<NamedPath> inputs;
  for (const std::string& path : args.inputs) inputs.push_back({"the input", path});
  check_distinct_outputs({{"--csv", args.csv}, {"--markdown", args.markdown}}, inputs);
  const OutputLock lock(args.csv, "--csv");  // not while a table or sweep is writing it
  CsvTable merged, first;
  // ((file, run_index), fields): --several-runs orders by file, then run_index (any index, up to
  // 2^64 - 1, stays within its file); one run's shards by run_index alone (file 0).
  std::vector<std::pair<std::pair<size_t, size_t>, std::vector<std::string>>> rows;
  size_t file_number = 0;
  std::map<std::string, std::string> seen;                         // configuration key -> file
  for (const std::string& path : args.inputs) {
    CsvTable t = read_csv(path);
    rebase_image_paths(t, path, args.csv);
    if (merged.columns.empty()) merged.columns = t.columns;
    if (t.columns != merged.columns)
      throw Error("'" + path + "' has other columns than '" + args.inputs.front() + "': cannot merge them");
    if (first.rows.empty()) first = t;
    if (!args.several_runs) check_same_run(t, first);
    const size_t scene = t.column("scene"), backend = t.column("backend"), mode = t.column("mode");
    for (size_t r = 0; r < t.rows.size(); ++r) {
      const size_t index = row_run_index(t, r, path);
      const std::string key = configuration_key(t.rows[r], t.columns);
      if (const auto it = seen.find(key); it != seen.end())
        throw Error("'" + path + "' and '" + it->second + "' both measure " + t.rows[r][scene] + " " + t.rows[r][backend] +
                    " " + t.rows[r][mode] + " (overlapping shards?)");
      seen[key] = path;
      rows.emplace_back(std::pair{args.several_runs ? file_number : 0, index}, std::move(t.rows[r]));
    }
    ++file_number;
  }
  // Back in the order of the unsharded run (of each run in turn, with --several-runs).
  std::stable_sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  size_t missing = 0, first_missing = 0;  // below the largest index: a shard not (yet) finished
  for (size_t i = 1; i < rows.size() && !args.several_runs; ++i) {
    const size_t before = rows[i - 1].first.second, index = rows[i].first.second;
    if (index == before)
      throw Error("run_index " + std::to_string(index) + " is in the inputs twice, with other configurations: they are not the shards of one run");
    if (index > before + 1) {
      if (missing == 0) first_missing = before + 1;
      missing += index - before - 1;
    }
  }
  for (auto& row : rows) merged.rows.push_back(std::move(row.second));
  write_csv(args.csv, merged);
  write_markdown(args.markdown, merged);
  std::cout << "merged " << merged.rows.size() << " rows from " << args.inputs.size() << " files into " << args.csv << "\n";
  if (missing)
    std::cerr << "note: " << missing << " configuration(s) below the last run_index are missing (first: run_index "
              << first_missing << "): is a shard unfinished?\n";
}

}  // namespace

void register_merge_command(CLI::App& app) {
  auto args = std::make_shared<MergeArgs>();
  CLI::App* cmd = app.add_subcommand("merge", "Join measurement CSVs (e.g. the shards of a table) into one");
  cmd->add_option("inputs", args->inputs, "CSV files written by table or sweep")->required();
  cmd->add_option("--csv", args->csv, "merged CSV")->required();
  cmd->add_option("--markdown", args->markdown, "also write the markdown tables of the merged rows");
  cmd->add_flag("--several-runs", args->several_runs,
                "join CSVs of different runs (e.g. a primary and a shadow table), one after the other; still refuses a configuration twice");
  cmd->callback([args] { run_merge(*args); });
}

}  // namespace sdfbench
