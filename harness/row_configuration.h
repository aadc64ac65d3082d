#pragma once
// The configuration a CSV row was measured with, read back from its key columns: what
// `sdfbench report --render-missing` renders a row's check frame from when the run kept no
// images. The inverse of configuration_fields() (benchmark_runner.h) for everything that
// changes a frame; a column missing from an older CSV keeps today's default.
#include "harness/benchmark_runner.h"
#include "harness/csv.h"

namespace sdfbench {

struct RowConfiguration {
  BenchConfig config;
  ImageSize check_size;
  std::string reference;
};

// Throws Error naming the file, row and column when a field is not a value the flag of the same
// name accepts.
RowConfiguration row_configuration(const CsvTable& table, size_t row);

}  // namespace sdfbench
