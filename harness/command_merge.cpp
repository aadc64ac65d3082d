// `sdfbench merge`: join the CSVs of shards (or of separate runs) into one, checking that they
// have the same columns and do not measure the same configuration twice.
#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <map>

#include "harness/commands.h"
#include "harness/csv.h"
#include "harness/measurement.h"
#include "harness/run_options.h"
#include "scenes/error.h"
#include "util/atomic_file.h"

namespace sdfbench {
namespace {

struct MergeArgs {
  std::vector<std::string> inputs;
  std::string csv, markdown;
};

void run_merge(const MergeArgs& args) {
  check_output_path(args.csv, "--csv");
  CsvTable merged;
  std::map<std::string, std::string> seen;  // configuration key -> file
  for (const std::string& path : args.inputs) {
    CsvTable t = read_csv(path);
    if (merged.columns.empty()) merged.columns = t.columns;
    if (t.columns != merged.columns)
      throw Error("'" + path + "' has other columns than '" + args.inputs.front() + "': cannot merge them");
    for (auto& row : t.rows) {
      const std::string key = configuration_key(row, t.columns);
      if (const auto it = seen.find(key); it != seen.end())
        throw Error("'" + path + "' and '" + it->second + "' both measure " + row[t.column("scene")] + " " +
                    row[t.column("backend")] + " " + row[t.column("mode")] + " (overlapping shards?)");
      seen[key] = path;
      merged.rows.push_back(std::move(row));
    }
  }
  // Back in the order of the unsharded run.
  const size_t index = merged.column("run_index");
  std::stable_sort(merged.rows.begin(), merged.rows.end(), [index](const auto& a, const auto& b) {
    return std::strtoull(a[index].c_str(), nullptr, 10) < std::strtoull(b[index].c_str(), nullptr, 10);
  });
  write_csv(args.csv, merged);
  write_markdown(args.markdown, merged);
  std::cout << "merged " << merged.rows.size() << " rows from " << args.inputs.size() << " files into " << args.csv << "\n";
}

}  // namespace

void register_merge_command(CLI::App& app) {
  auto args = std::make_shared<MergeArgs>();
  CLI::App* cmd = app.add_subcommand("merge", "Join measurement CSVs (e.g. the shards of a table) into one");
  cmd->add_option("inputs", args->inputs, "CSV files written by table or sweep")->required();
  cmd->add_option("--csv", args->csv, "merged CSV")->required();
  cmd->add_option("--markdown", args->markdown, "also write the markdown tables of the merged rows");
  cmd->callback([args] { run_merge(*args); });
}

}  // namespace sdfbench
