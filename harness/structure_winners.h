#pragma once
// "Which structure wins where", made from result rows: the rows of one file (one run, or the runs a
// `merge --several-runs` joined, one after the other on one machine) that measured the same
// scene, mode and frame size form a group (their ratios were measured side by side), and in each
// group the fastest row of each kind of method (Embree, a compute BVH, the driver's ray tracing,
// SDF with exact hits, SDF with a sampled field's own hits, triangles without a hierarchy) is
// picked. Rows that failed what they promised (a red verdict) are left out of the picking and
// counted; approximate rows (≈) compete in their own kind only.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "harness/csv.h"
#include "harness/row_verdict.h"

namespace sdfbench {

// The kind a row competes in, named for a reader, by its backend's declared kind
// (renderers/backend_registry.h) and its hit mode; a kind this file does not name competes under
// its declared name; empty for rows that do not compete (sdf-cpu, the reference CPU tracer, and
// backends this program does not know).
std::string competing_kind(const std::string& backend, const std::string& hit);

struct WinnerGroup {
  size_t file = 0;                          // index into the files given
  std::string scene, mode, size, overlap;   // overlap: the measured one, where the rows have it
  std::vector<std::optional<size_t>> best;  // per StructureWinners::kinds: the fastest row of that kind
  size_t failed = 0;                        // rows left out for a red verdict
  std::optional<size_t> winner;             // the kind index of the fastest best row that is no approximation
  std::optional<size_t> runner_up;          // the next fastest such kind (the winner's margin is over it)
  std::optional<size_t> vulkan_winner;      // ... among rows whose backend runs on the Vulkan device
};

struct StructureWinners {
  std::vector<std::string> kinds;  // the kinds present, in the order a reader scans them (Embree first, SDF last)
  std::vector<WinnerGroup> groups;  // in the files' order, then the rows' first appearance
};

// `verdict(file, row)`: the row's verdict as the caller reads it (the report adds ≠).
StructureWinners structure_winners(const std::vector<const CsvTable*>& files,
                                   const std::function<RowVerdict(size_t, size_t)>& verdict);

}  // namespace sdfbench
