// `sdfbench merge`: join the CSVs of shards (or of separate runs) into one, checking that they
// have the same columns, valid run indices and do not measure the same configuration twice.
#include <algorithm>
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
  if (!args.markdown.empty()) check_output_path(args.markdown, "--markdown");
  const OutputLock lock(args.csv, "--csv");  // not while a table or sweep is writing it
  CsvTable merged;
  std::vector<std::pair<size_t, std::vector<std::string>>> rows;  // run_index, fields
  std::map<std::string, std::string> seen;                         // configuration key -> file
  for (const std::string& path : args.inputs) {
    CsvTable t = read_csv(path);
    if (merged.columns.empty()) merged.columns = t.columns;
    if (t.columns != merged.columns)
      throw Error("'" + path + "' has other columns than '" + args.inputs.front() + "': cannot merge them");
    const size_t scene = t.column("scene"), backend = t.column("backend"), mode = t.column("mode");
    for (size_t r = 0; r < t.rows.size(); ++r) {
      const size_t index = row_run_index(t, r, path);
      const std::string key = configuration_key(t.rows[r], t.columns);
      if (const auto it = seen.find(key); it != seen.end())
        throw Error("'" + path + "' and '" + it->second + "' both measure " + t.rows[r][scene] + " " + t.rows[r][backend] +
                    " " + t.rows[r][mode] + " (overlapping shards?)");
      seen[key] = path;
      rows.emplace_back(index, std::move(t.rows[r]));
    }
  }
  // Back in the order of the unsharded run.
  std::stable_sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (auto& row : rows) merged.rows.push_back(std::move(row.second));
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
