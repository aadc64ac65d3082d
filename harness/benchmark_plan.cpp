#include "harness/benchmark_plan.h"

#include <charconv>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <set>
#include <sstream>

#include "harness/row_verdict.h"
#include "util/atomic_file.h"
#include "util/error.h"
#include "util/fnv1a.h"

namespace sdfbench {
namespace {

using Clock = std::chrono::steady_clock;

std::string duration_text(double seconds) {
  const long s = static_cast<long>(seconds + 0.5);
  char text[32];
  if (s >= 3600) std::snprintf(text, sizeof text, "%ldh%02ldm", s / 3600, (s / 60) % 60);
  else if (s >= 60) std::snprintf(text, sizeof text, "%ldm%02lds", s / 60, s % 60);
  else std::snprintf(text, sizeof text, "%lds", s);
  return text;
}

std::string describe(const BenchConfig& c) {
  std::ostringstream s;
  if (!c.table.empty()) s << "[" << c.table << "] ";
  s << c.scene << " " << c.backend << " " << to_string(c.mode) << " " << c.size.width << "x" << c.size.height;
  return s.str();
}

// An error in one configuration (e.g. a structure over the device's buffer limit) is a row
// saying so, not the end of a run of hours.
Measurement error_row(const BenchConfig& c, size_t index, const BenchSettings& settings, const std::string& message) {
  Measurement m = configuration_fields(c, index, settings);
  m.agreement = "ERROR: " + message;
  return m;
}

// A resumed file must hold rows of this very run: each row the configuration its run_index
// names in this plan, equal in every key column, and none twice. Anything else (a sweep's CSV
// resumed as a table, other flags) would mix measurements of different settings in one file.
std::set<std::string> resumed_keys(const CsvTable& table, const std::vector<BenchConfig>& plan, const BenchSettings& settings,
                                   const std::string& run_id) {
  const std::string file = "--resume: '" + table.source + "'";
  const std::string advice = ": it belongs to another run; resume with the flags of the run that wrote it, or use a new --csv";
  std::set<std::string> keys;
  for (size_t r = 0; r < table.rows.size(); ++r) {
    const std::string row = " row " + std::to_string(r + 1);
    const size_t index = row_run_index(table, r, table.source);
    if (index >= plan.size())
      throw Error(file + row + " has run_index " + std::to_string(index) + ", but this run has " +
                  std::to_string(plan.size()) + " configurations" + advice);
    const std::vector<std::string> ours = to_csv_fields(configuration_fields(plan[index], index, settings));
    for (const std::string& name : configuration_key_columns()) {
      const std::string& theirs = table.rows[r][table.column(name)];
      const std::string& wanted = ours[table.column(name)];  // same columns: checked by the caller
      if (theirs != wanted)
        throw Error(file + row + " (run_index " + std::to_string(index) + ") was measured with " + name + " '" + theirs +
                    "', this run asks for '" + wanted + "'" + advice);
    }
    if (!keys.insert(configuration_key(table.rows[r], table.columns)).second)
      throw Error(file + row + " measures run_index " + std::to_string(index) + " again; use a new --csv");
  }
  // Every row the configuration at its place, but a run of another list (e.g. more backends).
  for (size_t r = 0; r < table.rows.size(); ++r)
    if (const std::string& theirs = table.rows[r][table.column("run_id")]; theirs != run_id)
      throw Error(file + " row " + std::to_string(r + 1) + " comes from a run of another configuration list (run_id '" + theirs +
                  "', this run's is '" + run_id + "')" + advice);
  return keys;
}

}  // namespace

Shard parse_shard(const std::string& text) {
  Shard shard;
  const size_t slash = text.find('/');
  auto parse = [&](std::string_view part, unsigned& out) {
    const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), out);
    return !part.empty() && ec == std::errc() && end == part.data() + part.size();
  };
  if (slash == std::string::npos || !parse(std::string_view(text).substr(0, slash), shard.index) ||
      !parse(std::string_view(text).substr(slash + 1), shard.count) || shard.count < 1 || shard.index < 1 ||
      shard.index > shard.count)
    throw Error("--shard '" + text + "': expected K/N with 1 <= K <= N, e.g. 2/4");
  return shard;
}

bool in_shard(size_t i, const Shard& shard) { return i % shard.count == shard.index - 1; }

void check_plan_size(const std::vector<std::pair<std::string, size_t>>& axes) {
  size_t count = 1;
  bool over = false;  // past what a size_t holds
  std::string product;
  for (const auto& [name, length] : axes) {
    over = over || __builtin_mul_overflow(count, length, &count);
    product += (product.empty() ? "" : " x ") + name + " " + std::to_string(length);
  }
  if (over || count > kMaxPlanConfigurations)
    throw Error("the plan lists " + (over ? "more than " + std::to_string(SIZE_MAX) : std::to_string(count)) +
                " configurations (" + product + "), more than the limit of " + std::to_string(kMaxPlanConfigurations) +
                " per run: split it into several runs");
}

std::string plan_run_id(const std::vector<BenchConfig>& plan, const BenchSettings& settings) {
  uint64_t hash = fnv1a64(std::to_string(plan.size()));
  for (size_t i = 0; i < plan.size(); ++i) hash = fnv1a64(configuration_key(configuration_fields(plan[i], i, settings)) + '\n', hash);
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

CsvTable run_plan(const std::vector<BenchConfig>& plan, BenchmarkRunner& runner, const PlanOptions& options) {
  CsvTable table;
  table.columns = measurement_columns();
  const std::string run_id = plan_run_id(plan, runner.settings());
  runner.set_run_id(run_id);
  std::optional<OutputLock> lock;  // held for the whole run: another run on this CSV would replace its rows
  std::set<std::string> done;
  if (!options.csv.empty()) {
    check_output_path(options.csv, "--csv");
    lock.emplace(options.csv, "--csv");
    if (options.resume && std::filesystem::exists(options.csv)) {
      table = read_csv(options.csv);
      if (table.columns != measurement_columns())
        throw Error("--resume: '" + options.csv + "' has other columns than this sdfbench writes; use a new --csv file");
      done = resumed_keys(table, plan, runner.settings(), run_id);
      // A configuration that failed (an ERROR row: a cap, a lost device, a killed job) is run
      // again: its row is dropped here and written anew.
      size_t failed = 0;
      for (size_t r = table.rows.size(); r-- > 0;)
        if (row_verdict(table, table.rows[r]).is_error()) {
          done.erase(configuration_key(table.rows[r], table.columns));
          table.rows.erase(table.rows.begin() + static_cast<std::ptrdiff_t>(r));
          ++failed;
        }
      if (failed) std::cerr << "resume: retrying " << failed << " configuration(s) that failed before (ERROR rows)\n";
    } else if (!options.resume && std::filesystem::exists(options.csv)) {
      std::cerr << "note: overwriting '" << options.csv << "' (--resume continues a file instead)\n";
    }
  }

  std::vector<size_t> todo;
  size_t resumed = 0;
  for (size_t i = 0; i < plan.size(); ++i) {
    if (!in_shard(i, options.shard)) continue;
    if (done.count(configuration_key(configuration_fields(plan[i], i, runner.settings())))) ++resumed;
    else todo.push_back(i);
  }
  if (resumed) std::cerr << "resume: " << resumed << " configuration(s) already in '" << options.csv << "'\n";

  // A shard with nothing (left) to run still writes its file, so a merge of every shard's CSV works.
  if (!options.csv.empty() && todo.empty()) write_csv(options.csv, table);
  const Clock::time_point start = Clock::now();
  for (size_t k = 0; k < todo.size(); ++k) {
    const BenchConfig& config = plan[todo[k]];
    const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    std::cerr << "[" << (k + 1) << "/" << todo.size() << "] " << describe(config) << "  (elapsed " << duration_text(elapsed);
    if (k > 0) std::cerr << ", ~" << duration_text(elapsed / static_cast<double>(k) * static_cast<double>(todo.size() - k)) << " left";
    std::cerr << ")\n" << std::flush;
    Measurement m;
    try {
      m = runner.run(config, todo[k]);
    } catch (const Error& e) {
      m = error_row(config, todo[k], runner.settings(), e.what());
      std::cerr << "  error: " << e.what() << "\n";
    }
    m.run_id = run_id;
    std::printf("  %-10s %-8s %9.3f ms  %8.2f FPS  %7.3f Mrays/s  %s%s\n", m.backend.c_str(), m.mode.c_str(), m.ms_median,
                m.fps, m.mrays_per_s, m.agreement.c_str(), m.budget_cut ? "  (budget cut)" : "");
    std::fflush(stdout);
    table.rows.push_back(to_csv_fields(m));
    if (!options.csv.empty()) write_csv(options.csv, table);
  }
  return table;
}

}  // namespace sdfbench
