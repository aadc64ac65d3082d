#include "harness/row_configuration.h"

#include <charconv>
#include <cmath>

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
  template <typename T>
  std::optional<T> number(const std::string& column) const {
    const std::string field = text(column);
    if (field.empty()) return std::nullopt;
    double v = 0;
    const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), v);
    if (ec != std::errc() || end != field.data() + field.size() || !std::isfinite(v) || v < 0)
      throw Error(where(column) + ": '" + field + "' is not a non-negative number");
    return static_cast<T>(v);
  }
  template <typename T>
  void read(const std::string& column, T& target) const {
    if (const std::optional<T> v = number<T>(column)) target = *v;
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
  if (c.scene.empty()) throw Error(r.where("scene") + ": empty");
  const std::optional<RenderMode> mode = parse_render_mode(r.text("mode"));
  if (!mode) throw Error(r.where("mode") + ": '" + r.text("mode") + "' is not primary, shadow or whitted");
  c.mode = *mode;
  r.read("max_depth", c.max_depth);
  c.size = parse_size(r.text("width") + "x" + r.text("height"), r.where("width/height"));
  out.check_size = parse_size(r.text("check_size").empty() ? "320x180" : r.text("check_size"), r.where("check_size"));
  out.reference = r.text("reference").empty() ? "embree" : r.text("reference");

  BackendOptions& o = c.options;
  if (!r.text("requested_device").empty()) o.device = r.text("requested_device");
  r.read("threads", o.threads);
  const std::string passes = r.text("whitted_passes");
  if (passes == "on" || passes == "off") o.whitted_passes = passes == "on";
  if (r.number<double>("hash_cell")) o.hash_cell_given = true;
  r.read("hash_cell", o.scene_hash.hash_cell);
  r.read("octree_depth", o.scene_hash.octree_depth);
  r.read("octree_min_objects", o.scene_hash.octree_min_objects);
  r.read("octree_min_size", o.scene_hash.octree_min_size);
  if (const std::string lists = r.text("lists"); !lists.empty()) {
    if (lists != "exact" && lists != "thesis") throw Error(r.where("lists") + ": '" + lists + "' is not exact or thesis");
    o.scene_hash.lists = lists == "exact" ? sdf::ListRule::Exact : sdf::ListRule::Thesis;
  }
  r.read("mesh_cell", o.mesh_grid.cell_size);
  r.read("cells_per_extent", o.mesh_grid.cells_per_extent);
  if (r.text("fixed_grid") == "1") o.mesh_grid.scale_with_triangles = false;
  if (const std::optional<double> mb = r.number<double>("max_structure_mb"))
    o.mesh_grid.max_bytes = o.scene_hash.max_bytes = static_cast<uint64_t>(*mb) << 20;
  sdf::SphereTraceParams& t = o.tracing;
  if (const std::string hit = r.text("hit"); !hit.empty()) {
    if (hit != "exact" && hit != "thesis" && hit != "field") throw Error(r.where("hit") + ": '" + hit + "' is not exact, thesis or field");
    t.hit = hit == "exact" ? sdf::HitMode::exact : hit == "thesis" ? sdf::HitMode::thesis : sdf::HitMode::field;
  }
  r.read("max_steps", t.max_steps);
  r.read("hit_epsilon", t.hit_epsilon);
  r.read("hit_footprint", t.footprint);
  r.read("over_relax", t.over_relax);
  t.cell_bound = r.text("cell_bound") == "1";
  t.storage_tables = r.text("storage_tables") == "1";
  for (const ParamSpec& spec : param_specs()) {
    const std::string value = r.text(spec.name);
    if (value.empty()) continue;
    if (const std::string problem = check_param_value(spec, value); !problem.empty())
      throw Error(r.where(spec.name) + ": " + problem);
    o.params.set(spec.name, value);
  }
  return out;
}

}  // namespace sdfbench
