#pragma once
// Runs a list of configurations (a table or a sweep): the K-th of N shards, skipping rows a
// previous run already wrote (--resume), with a progress line on stderr and the CSV rewritten
// atomically after every row, so a killed run leaves a valid file that --resume completes.
#include <optional>
#include <string>
#include <vector>

#include "harness/benchmark_runner.h"
#include "harness/csv.h"

namespace sdfbench {

struct Shard {
  unsigned index = 1, count = 1;  // 1-based: "--shard 2/4" is index 2 of count 4
};
// "K/N" with 1 <= K <= N; throws Error naming --shard otherwise.
Shard parse_shard(const std::string& text);
// Configuration i (0-based) belongs to shard K of N when i % N == K - 1: round robin, so every
// shard gets a share of the slow (large) configurations.
bool in_shard(size_t i, const Shard& shard);

struct PlanOptions {
  std::string csv;  // empty: no CSV
  bool resume = false;
  Shard shard;
};

// The most configurations one table or sweep may list: at a second each, more than a day. The
// count is known before anything is built, so a larger product of lists is refused at once.
constexpr size_t kMaxPlanConfigurations = 100000;
// Throws Error with the count, each axis ("--hash-cell 5000") and the limit when the product of
// the axes' lengths passes kMaxPlanConfigurations (computed without overflow).
void check_plan_size(const std::vector<std::pair<std::string, size_t>>& axes);

// The run's id (CSV column run_id): a digest of every configuration's key in the whole plan,
// so all shards of one run share it and a run with any other setting or list has another.
std::string plan_run_id(const std::vector<BenchConfig>& plan, const BenchSettings& settings);

// Returns the CSV table of this run's rows (those resumed from the file included).
CsvTable run_plan(const std::vector<BenchConfig>& plan, BenchmarkRunner& runner, const PlanOptions& options);

}  // namespace sdfbench
