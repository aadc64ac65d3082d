#include "harness/measurement.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <concepts>
#include <cstdio>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <set>

#include "renderers/backend_registry.h"
#include "util/error.h"
#include "util/number_text.h"


namespace sdfbench {

std::string csv_number(double v) { return six_digits(v); }

namespace {

// A field as the CSV writes it: text as is, integers in decimal, numbers by csv_number, flags 1/0,
// an empty optional as an empty cell.
std::string cell(const std::string& v) { return v; }
std::string cell(double v) { return csv_number(v); }
std::string cell(bool v) { return v ? "1" : "0"; }
template <std::unsigned_integral T>
std::string cell(T v) { return std::to_string(v); }
template <class T>
std::string cell(const std::optional<T>& v) { return v ? cell(*v) : ""; }

// One CSV column: its name and how a Measurement writes it.
struct Column {
  std::string name;
  std::function<std::string(const Measurement&)> write;
};
// A column named as the Measurement field it writes.
#define FIELD_COLUMN(field) Column{#field, [](const Measurement& m) { return cell(m.field); }}

// The CSV's columns in their order (README, "CSV columns"; committed CSVs are read back by name,
// but keep the order). The backends' parameters and the work counters come from their tables.
const std::vector<Column>& csv_columns() {
  static const std::vector<Column> columns = [] {
    std::vector<Column> c = {FIELD_COLUMN(run_index), FIELD_COLUMN(run_id), FIELD_COLUMN(table), FIELD_COLUMN(scene),
                             FIELD_COLUMN(mesh), FIELD_COLUMN(triangles), FIELD_COLUMN(objects), FIELD_COLUMN(overlap),
                             FIELD_COLUMN(backend), FIELD_COLUMN(mode), FIELD_COLUMN(max_depth), FIELD_COLUMN(width),
                             FIELD_COLUMN(height)};
    for (const ParamSpec& spec : param_catalogue())
      c.push_back({spec.name, [name = spec.name](const Measurement& m) {
                     const auto it = m.backend_params.find(name);
                     return it != m.backend_params.end() ? it->second : "";
                   }});
    c.insert(c.end(), {FIELD_COLUMN(cache), FIELD_COLUMN(on_bad_cache), FIELD_COLUMN(requested_frames),
                       FIELD_COLUMN(warmup), FIELD_COLUMN(budget_s), FIELD_COLUMN(reference),
                       FIELD_COLUMN(requested_device), FIELD_COLUMN(whitted_passes), FIELD_COLUMN(validate),
                       FIELD_COLUMN(frames), FIELD_COLUMN(clock), FIELD_COLUMN(ms_median), FIELD_COLUMN(ms_min),
                       FIELD_COLUMN(ms_max), FIELD_COLUMN(ms_wall_median), FIELD_COLUMN(fps), FIELD_COLUMN(mrays_per_s),
                       FIELD_COLUMN(rays_per_pixel)});
    for (uint32_t k = 0; k < COUNTER_KINDS; ++k)
      c.push_back({counter_columns()[k], [k](const Measurement& m) { return cell(m.per_ray[k]); }});
    c.insert(c.end(), {FIELD_COLUMN(prepare_ms), FIELD_COLUMN(build_ms), FIELD_COLUMN(structure_bytes),
                       FIELD_COLUMN(tree_sah), FIELD_COLUMN(tree_epo), FIELD_COLUMN(tree_nodes), FIELD_COLUMN(backend_resolved), FIELD_COLUMN(check_size), FIELD_COLUMN(hit_agreement),
                       FIELD_COLUMN(id_agreement), FIELD_COLUMN(psnr), FIELD_COLUMN(depth_p99),
                       FIELD_COLUMN(depth_p99_voxels), FIELD_COLUMN(agreement), FIELD_COLUMN(budget_cut),
                       FIELD_COLUMN(load_avg), FIELD_COLUMN(cpu_steal_pct), FIELD_COLUMN(cpu_other_pct), FIELD_COLUMN(busy),
                       FIELD_COLUMN(frame_image), FIELD_COLUMN(reference_image), FIELD_COLUMN(diff_image),
                       FIELD_COLUMN(device), FIELD_COLUMN(driver), FIELD_COLUMN(embree), FIELD_COLUMN(cpu),
                       FIELD_COLUMN(threads), FIELD_COLUMN(commit)});
    return c;
  }();
  return columns;
}
#undef FIELD_COLUMN

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

const std::array<std::string, COUNTER_KINDS>& counter_columns() {
  static const std::array<std::string, COUNTER_KINDS> columns = [] {
    std::array<std::string, COUNTER_KINDS> c;
    for (uint32_t k = 0; k < COUNTER_KINDS; ++k) c[k] = std::string(counter_names()[k]) + "_per_ray";
    return c;
  }();
  return columns;
}

const std::vector<std::string>& measurement_columns() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const Column& c : csv_columns()) n.push_back(c.name);
    return n;
  }();
  return names;
}

std::vector<std::string> to_csv_fields(const Measurement& m) {
  std::vector<std::string> fields;
  for (const Column& c : csv_columns()) fields.push_back(c.write(m));
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
