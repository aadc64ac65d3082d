#pragma once
// A run's rows as Google Benchmark's JSON (`table`/`sweep --json FILE`), so that its tools read
// them: Debian's libbenchmark-tools `compare.py benchmarks A.json B.json` compares two runs row by
// row. One benchmark per row, named by what sets it apart (scene/backend/mode/size and every key
// column that varies in the run); real_time is the median frame time (ms); sdfbench measures no
// CPU time, so cpu_time repeats it; Mrays/s, FPS, the work counters, the agreement figures and
// the structure's bytes and build time are user counters. ERROR rows carry error_occurred (and no
// time, so that compare.py leaves them out). docs/commands.md, "JSON for Google Benchmark's tools".
#include <string>

#include "harness/csv.h"

namespace sdfbench {

std::string benchmark_json(const CsvTable& rows);

}  // namespace sdfbench
