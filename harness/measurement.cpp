#include "harness/measurement.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>
#include <set>

#include "renderers/backend_registry.h"
#include "util/error.h"


namespace sdfbench {

std::string csv_number(double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

namespace {

std::string number(double v) { return csv_number(v); }
std::string number(const std::optional<double>& v) { return v ? number(*v) : ""; }

// The backends' parameters (renderers/backend_registry.h) stand where "params" does.
std::vector<std::string> with_backend_params(std::vector<std::string> columns) {
  auto at = columns.erase(std::find(columns.begin(), columns.end(), "params"));
  for (const ParamSpec& spec : param_catalogue()) at = columns.insert(at, spec.name) + 1;
  return columns;
}

// Everything configuration_fields() fills: what was asked for, not what happened (frames, the
// timed frames actually run, and device, the device found, are left out; requested_frames and
// requested_device are in).
const std::vector<std::string>& key_columns() {
  static const std::vector<std::string> columns = with_backend_params(
      {"table", "scene", "backend", "mode", "max_depth", "width", "height", "params", "cache", "on_bad_cache", "requested_frames",
       "warmup", "budget_s", "check_size", "reference", "requested_device", "whitted_passes", "validate", "threads"});
  return columns;
}

}  // namespace

const std::vector<std::string>& measurement_columns() {
  static const std::vector<std::string> columns = with_backend_params({
      "run_index", "run_id", "table", "scene", "mesh", "triangles", "objects", "overlap", "backend", "mode", "max_depth", "width", "height",
      "params", "cache", "on_bad_cache", "requested_frames", "warmup", "budget_s", "reference",
      "requested_device", "whitted_passes", "validate", "frames", "clock", "ms_median", "ms_min", "ms_max",
      "ms_wall_median", "fps", "mrays_per_s", "rays_per_pixel", "steps_per_ray", "instance_evals_per_ray",
      "triangle_evals_per_ray", "aabb_tests_per_ray", "triangle_tests_per_ray", "out_of_steps_per_ray", "field_samples_per_ray", "cell_sets_per_ray", "prepare_ms", "build_ms", "structure_bytes", "backend_resolved", "check_size", "hit_agreement",
      "id_agreement", "psnr", "depth_p99", "depth_p99_voxels", "agreement", "budget_cut", "load_avg", "cpu_steal_pct", "cpu_other_pct", "busy", "frame_image", "reference_image", "diff_image", "device", "driver", "embree", "cpu", "threads", "commit"});
  return columns;
}

std::vector<std::string> to_csv_fields(const Measurement& m) {
  std::vector<std::string> fields = {std::to_string(m.run_index), m.run_id, m.table, m.scene, m.mesh, std::to_string(m.triangles), std::to_string(m.objects), number(m.overlap),
          m.backend, m.mode, std::to_string(m.max_depth), std::to_string(m.width), std::to_string(m.height),
          m.cache, m.on_bad_cache, std::to_string(m.requested_frames), std::to_string(m.warmup), number(m.budget_s),
          m.reference, m.requested_device, m.whitted_passes, m.validate ? "1" : "0", std::to_string(m.frames), m.clock, number(m.ms_median), number(m.ms_min), number(m.ms_max),
          number(m.ms_wall_median), number(m.fps), number(m.mrays_per_s), number(m.rays_per_pixel),
          number(m.steps_per_ray), number(m.instance_evals_per_ray), number(m.triangle_evals_per_ray),
          number(m.aabb_tests_per_ray), number(m.triangle_tests_per_ray), number(m.out_of_steps_per_ray), number(m.field_samples_per_ray), number(m.cell_sets_per_ray),
          number(m.prepare_ms), number(m.build_ms), number(m.structure_bytes), m.backend_resolved, m.check_size, number(m.hit_agreement),
          number(m.id_agreement), number(m.psnr), number(m.depth_p99), number(m.depth_p99_voxels), m.agreement, m.budget_cut ? "1" : "0",
          number(m.load_avg), number(m.cpu_steal_pct), number(m.cpu_other_pct), m.busy ? (*m.busy ? "1" : "0") : "", m.frame_image, m.reference_image, m.diff_image, m.device, m.driver, m.embree,
          m.cpu, std::to_string(m.threads), m.commit};
  const std::vector<std::string>& columns = measurement_columns();
  auto at = fields.begin() + (std::find(columns.begin(), columns.end(), "height") - columns.begin() + 1);
  for (const ParamSpec& spec : param_catalogue()) {
    const auto it = m.backend_params.find(spec.name);
    at = fields.insert(at, it != m.backend_params.end() ? it->second : "") + 1;
  }
  return fields;
}

std::string configuration_key(const std::vector<std::string>& fields, const std::vector<std::string>& columns) {
  std::string key;
  for (const std::string& name : key_columns())
    for (size_t i = 0; i < columns.size(); ++i)
      if (columns[i] == name) key += fields.at(i) + '|';
  return key;
}

std::string configuration_key(const Measurement& m) { return configuration_key(to_csv_fields(m), measurement_columns()); }

const std::vector<std::string>& configuration_key_columns() { return key_columns(); }

std::string run_difference(const CsvTable& a, const CsvTable& b) {
  const std::string in_a = " in '" + a.source + "', ", in_b = " in '" + b.source + "'";
  std::map<size_t, size_t> rows_of_b;  // run_index -> row
  for (size_t r = 0; r < b.rows.size(); ++r) rows_of_b.emplace(row_run_index(b, r, b.source), r);
  for (size_t r = 0; r < a.rows.size(); ++r) {
    const auto it = rows_of_b.find(row_run_index(a, r, a.source));
    if (it == rows_of_b.end()) continue;
    for (const std::string& name : key_columns()) {
      const std::string &x = a.rows[r][a.column(name)], &y = b.rows[it->second][b.column(name)];
      if (x != y) return "run_index " + std::to_string(it->first) + " has " + name + " '" + x + "'" + in_a + "'" + y + "'" + in_b;
    }
  }
  auto uniform = [](const CsvTable& t, size_t column) -> std::optional<std::string> {
    for (const auto& row : t.rows)
      if (row[column] != t.rows.front()[column]) return std::nullopt;
    return t.rows.empty() ? std::nullopt : std::optional(t.rows.front()[column]);
  };
  // Run-wide settings first; any other column (backend, scene, a sweep axis) may just be what
  // one shard of a run holds, so it is only an example.
  const std::set<std::string> run_wide = {"width", "height", "max_depth", "requested_frames", "warmup", "budget_s", "check_size",
                                          "reference", "requested_device", "whitted_passes", "validate", "threads"};
  std::string example;
  for (const std::string& name : key_columns()) {
    const auto x = uniform(a, a.column(name)), y = uniform(b, b.column(name));
    if (!x || !y || *x == *y) continue;
    const std::string difference = name + " '" + *x + "'" + in_a + "'" + *y + "'" + in_b;
    if (run_wide.count(name)) return difference;
    if (example.empty()) example = " (e.g. " + difference + ")";
  }
  return "they list other configurations" + example;
}

size_t row_run_index(const CsvTable& table, size_t row, const std::string& source) {
  const std::string& text = table.rows.at(row)[table.column("run_index")];
  size_t index = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), index);
  const bool digits = !text.empty() && end == text.data() + text.size();
  if (digits && ec == std::errc::result_out_of_range)
    throw Error("'" + source + "' row " + std::to_string(row + 1) + ": run_index '" + text +
                "' is not a non-negative integer up to " + std::to_string(std::numeric_limits<size_t>::max()) + " (out of range)");
  if (!digits || ec != std::errc())
    throw Error("'" + source + "' row " + std::to_string(row + 1) + ": run_index '" + text +
                "' is not a non-negative integer");
  return index;
}

}  // namespace sdfbench
