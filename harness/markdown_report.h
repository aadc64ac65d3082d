#pragma once
// Markdown views of a measurement CSV: the thesis' tables laid out like the thesis (rows
// meshes, columns object counts) with the thesis' value beside ours, the 6.1/6.3 speed-up,
// every backend side by side per mode, the overlap table (a row per k, every backend, each
// distance field over each hierarchy), and sweeps. Flagged cells carry the row's marks
// (harness/row_verdict.h: ERROR, ✗, ✂, V, † and ‡), explained below the tables.
#include <string>

#include "harness/csv.h"
#include "harness/thesis_tables.h"

namespace sdfbench {

std::string markdown_report(const CsvTable& rows, const ThesisTables& thesis);

}  // namespace sdfbench
