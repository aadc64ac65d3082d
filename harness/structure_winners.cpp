#include "harness/structure_winners.h"

#include <algorithm>
#include <cstdlib>
#include <map>
#include <tuple>

#include "renderers/backend_registry.h"

namespace sdfbench {
namespace {

// Declared kinds as a reader names them, in the order the table's columns take.
const std::vector<std::pair<std::string, std::string>>& named_kinds() {
  static const std::vector<std::pair<std::string, std::string>> kinds = {
      {"cpu-bvh", "Embree (CPU)"},     {"compute-bvh", "compute BVH"},        {"driver-rt", "driver ray tracing"},
      {"triangles", "triangles, no hierarchy"}, {"sdf:exact", "SDF, exact hits"}, {"sdf:thesis", "SDF, thesis' hits"},
      {"sdf:field", "SDF, field hits (≈)"}};
  return kinds;
}

// A row's Mrays/s (0 where the CSV has none).
double mrays(const CsvTable& t, size_t row) {
  return t.has_column("mrays_per_s") ? std::atof(t.rows[row][t.column("mrays_per_s")].c_str()) : 0.0;
}

}  // namespace

std::string competing_kind(const std::string& backend, const std::string& hit) {
  const auto& all = backends();
  const auto info = std::find_if(all.begin(), all.end(), [&](const BackendInfo& b) { return b.name == backend; });
  if (info == all.end() || info->kind == BackendKind::SdfCpu) return "";
  std::string kind = to_string(info->kind);
  if (is_sdf(info->kind)) kind = "sdf:" + (hit == "field" || hit == "thesis" ? hit : "exact");
  for (const auto& [declared, name] : named_kinds())
    if (declared == kind) return name;
  return kind;
}

StructureWinners structure_winners(const std::vector<const CsvTable*>& files,
                                   const std::function<RowVerdict(size_t, size_t)>& verdict) {
  // Each group's fastest row per kind, the kinds by name until every row is seen.
  std::vector<std::map<std::string, size_t>> best_by_kind;
  std::vector<std::string> seen;
  StructureWinners out;
  for (size_t f = 0; f < files.size(); ++f) {
    const CsvTable& t = *files[f];
    const auto text = [&](size_t row, const char* column) -> std::string {
      return t.has_column(column) ? t.rows[row][t.column(column)] : std::string();
    };
    const auto speed = [&](size_t row) { return mrays(t, row); };
    // (scene, mode, size) -> group; a merged file's runs (e.g. one sweep per backend) ran one
    // after the other on one machine and are set side by side, as the merge asked
    std::map<std::tuple<std::string, std::string, std::string>, size_t> index;
    for (size_t r = 0; r < t.rows.size(); ++r) {
      const std::string kind = competing_kind(text(r, "backend"), text(r, "hit"));
      if (kind.empty()) continue;
      const std::string size = text(r, "width") + "x" + text(r, "height");
      auto [at, added] = index.try_emplace(std::make_tuple(text(r, "scene"), text(r, "mode"), size), out.groups.size());
      if (added) {
        out.groups.push_back({f, text(r, "scene"), text(r, "mode"), size, text(r, "overlap"), {}, 0, std::nullopt});
        best_by_kind.emplace_back();
      }
      if (verdict(f, r).is_failure()) {
        ++out.groups[at->second].failed;
        continue;
      }
      if (std::find(seen.begin(), seen.end(), kind) == seen.end()) seen.push_back(kind);
      auto [best, first] = best_by_kind[at->second].try_emplace(kind, r);
      if (!first && speed(r) > speed(best->second)) best->second = r;
    }
  }
  // Columns: the named kinds in their order, then any other declared kind as first seen.
  for (const auto& [declared, name] : named_kinds())
    if (std::find(seen.begin(), seen.end(), name) != seen.end()) out.kinds.push_back(name);
  for (const std::string& kind : seen)
    if (std::find(out.kinds.begin(), out.kinds.end(), kind) == out.kinds.end()) out.kinds.push_back(kind);
  for (size_t g = 0; g < out.groups.size(); ++g) {
    WinnerGroup& group = out.groups[g];
    const CsvTable& t = *files[group.file];
    const auto speed = [&](size_t row) { return mrays(t, row); };
    const auto faster = [&](size_t k, const std::optional<size_t>& than) { return !than || speed(*group.best[k]) > speed(*group.best[*than]); };
    group.best.resize(out.kinds.size());
    for (size_t k = 0; k < out.kinds.size(); ++k) {
      const auto found = best_by_kind[g].find(out.kinds[k]);
      if (found == best_by_kind[g].end()) continue;
      group.best[k] = found->second;
      // An approximation (field hits) is shown in its own kind but does not win: its image is not the reference's.
      if (verdict(group.file, found->second).is_approximate()) continue;
      if (faster(k, group.winner)) {
        group.runner_up = group.winner;
        group.winner = k;
      } else if (faster(k, group.runner_up)) {
        group.runner_up = k;
      }
      if (backend_info(t.rows[found->second][t.column("backend")]).vulkan && faster(k, group.vulkan_winner)) group.vulkan_winner = k;
    }
  }
  return out;
}

}  // namespace sdfbench
