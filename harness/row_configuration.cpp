#include "harness/row_configuration.h"

#include <charconv>
#include <cmath>

#include "renderers/backend_registry.h"
#include "renderers/shading/gpu_types.h"
#include "util/error.h"

namespace sdfbench {
namespace {

// Row `row` of `table`, read by column name, with errors naming the file, row and column.
struct RowReader {
  const CsvTable& table;
  size_t row;

  std::string where(const std::string& column) const {
    return "'" + table.source + "' row " + std::to_string(row + 1) + ", column " + column;
  }
  // Empty when the column is missing (an older CSV) or the field is empty.
  std::string text(const std::string& column) const {
    return table.has_column(column) ? table.rows.at(row)[table.column(column)] : std::string();
  }
  // An integer in [0, hi] (the range of the flag of the same name).
  template <typename T>
  void read(const std::string& column, T& target, T hi) const {
    const std::string field = text(column);
    if (field.empty()) return;
    double v = 0;
    const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), v);
    if (ec != std::errc() || end != field.data() + field.size() || !(v >= 0 && v <= static_cast<double>(hi)) || v != std::floor(v))
      throw Error(where(column) + ": '" + field + "' is not an integer in [0, " + std::to_string(hi) + "]");
    target = static_cast<T>(v);
  }
};

}  // namespace

RowConfiguration row_configuration(const CsvTable& table, size_t row) {
  const RowReader r{table, row};
  RowConfiguration out;
  BenchConfig& c = out.config;
  c.table = r.text("table");
  c.scene = r.text("scene");
  c.backend = r.text("backend");
  try {
    check_backend_name(c.backend);
  } catch (const Error& e) {
    throw Error(r.where("backend") + ": " + e.what());
  }
  if (c.scene.empty()) throw Error(r.where("scene") + ": empty");
  const std::optional<RenderMode> mode = parse_render_mode(r.text("mode"));
  if (!mode) throw Error(r.where("mode") + ": '" + r.text("mode") + "' is not primary, shadow or whitted");
  c.mode = *mode;
  r.read("max_depth", c.max_depth, MAX_DEPTH_LIMIT);
  c.size = parse_size(r.text("width") + "x" + r.text("height"), r.where("width/height"));
  out.check_size = parse_size(r.text("check_size").empty() ? "320x180" : r.text("check_size"), r.where("check_size"));
  out.reference = r.text("reference").empty() ? "embree" : r.text("reference");

  BackendOptions& o = c.options;
  if (!r.text("requested_device").empty()) o.device = r.text("requested_device");
  r.read("threads", o.threads, 1024u);
  const std::string passes = r.text("whitted_passes");
  if (passes == "on" || passes == "off") o.whitted_passes = passes == "on";
  // The backend's own parameters, checked as their flags check them (against this backend's
  // choices). A column of a parameter the backend does not own is left out: older CSVs recorded
  // what such a backend did implicitly (sdf-hash's octree depth 0, sdf-global's unused hash).
  const BackendInfo& backend = backend_info(c.backend);
  for (const ParamSpec& spec : backend.params) {
    const std::string value = r.text(spec.name);
    if (value.empty()) continue;
    std::string why;
    const std::string canonical = canonical_param_value(spec, value, why);
    if (!why.empty()) throw Error(r.where(spec.name) + ": " + why + " (as " + flag_of(spec) + " of " + backend.name + ")");
    o.params.set(spec.name, canonical);
  }
  return out;
}

}  // namespace sdfbench
