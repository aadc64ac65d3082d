#include "harness/markdown_report.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <set>
#include <sstream>

#include "harness/measurement.h"
#include "harness/overlap_axis.h"
#include "harness/row_verdict.h"
#include "renderers/backend_registry.h"

namespace sdfbench {
namespace {

// A row, read by column name.
struct Row {
  const CsvTable* table;
  const std::vector<std::string>* fields;
  const std::string& operator[](const std::string& column) const { return fields->at(table->column(column)); }
  double number(const std::string& column) const { return std::atof((*this)[column].c_str()); }
  RowVerdict verdict() const { return row_verdict(*table, *fields); }
};

std::vector<Row> rows_of(const CsvTable& csv) {
  std::vector<Row> rows;
  for (const auto& fields : csv.rows) rows.push_back({&csv, &fields});
  return rows;
}

std::string fixed(double v, int digits) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", digits, v);
  return text;
}

bool truncated(const Row& r) { return r.verdict().has(Mark::truncated); }

// A speed (`column`: fps or mrays_per_s) with ~3 significant digits, and the row's marks
// (harness/row_verdict.h); an ERROR row has no speed, its mark stands in for it.
std::string speed_cell(const Row& r, const std::string& column) {
  const RowVerdict verdict = r.verdict();
  if (verdict.is_error()) return verdict.symbols();
  const double v = r.number(column);
  const std::string text = fixed(v, v >= 100 ? 0 : v >= 10 ? 1 : v >= 1 ? 2 : 3);
  return verdict.marks.empty() ? text : text + " " + verdict.symbols();
}

std::string fps_cell(const Row& r) { return speed_cell(r, "fps"); }

std::string thesis_cell(const ThesisValue& v) { return v.upper_bound ? "<1" : fixed(v.fps, v.fps >= 10 ? 0 : 1); }

std::string sizes_of(const std::vector<Row>& rows) {
  std::set<std::string> sizes;
  for (const Row& r : rows) sizes.insert(r["width"] + "x" + r["height"]);
  std::string text;
  for (const std::string& s : sizes) text += (text.empty() ? "" : ", ") + s;
  return text;
}

std::vector<std::string> ordered_meshes(const std::vector<Row>& rows) {
  std::vector<std::string> meshes;
  for (const Row& r : rows)
    if (std::find(meshes.begin(), meshes.end(), r["mesh"]) == meshes.end()) meshes.push_back(r["mesh"]);
  return meshes;
}

std::vector<size_t> ordered_counts(const std::vector<Row>& rows) {
  std::set<size_t> counts;
  for (const Row& r : rows) counts.insert(static_cast<size_t>(r.number("objects")));
  return {counts.begin(), counts.end()};
}

const Row* find_row(const std::vector<Row>& rows, const std::string& mesh, size_t objects) {
  for (const Row& r : rows)
    if (r["mesh"] == mesh && static_cast<size_t>(r.number("objects")) == objects) return &r;
  return nullptr;
}

void header(std::ostringstream& out, const std::string& first, const std::vector<size_t>& counts) {
  out << "| " << first << " |";
  for (size_t c : counts) out << " " << c << " |";
  out << "\n|---|";
  for (size_t i = 0; i < counts.size(); ++i) out << "---:|";
  out << "\n";
}

void thesis_table(std::ostringstream& out, const ThesisTableConfig& config, const std::vector<Row>& rows,
                  const ThesisTables& thesis) {
  out << "### Table " << config.id << ": " << config.backend << ", " << to_string(config.mode) << " (" << sizes_of(rows)
      << ")\n\n" << config.description << ". FPS measured here, the thesis' value in brackets (GTX 1070, 1280x720).\n\n";
  const std::vector<size_t> counts = ordered_counts(rows);
  header(out, "mesh \\ objects", counts);
  for (const std::string& mesh : ordered_meshes(rows)) {
    out << "| " << mesh << " |";
    for (size_t c : counts) {
      const Row* r = find_row(rows, mesh, c);
      const auto t = thesis.find(config.id, mesh, c);
      out << " " << (r ? fps_cell(*r) : "–") << (t ? " (" + thesis_cell(*t) + ")" : "") << " |";
    }
    out << "\n";
  }
  out << "\n";
}

// a's FPS / b's ("2.50x"; ✂ when either was cut short), "–" without both.
std::string ratio_cell(const Row* a, const Row* b) {
  std::string cell = a && b && b->number("fps") > 0 ? fixed(a->number("fps") / b->number("fps"), 2) + "x" : "–";
  if (a && b && (truncated(*a) || truncated(*b))) cell += " ✂";
  return cell;
}

// mesh x objects: FPS of `numerator`'s row / FPS of `denominator`'s, then `note(mesh, objects)`.
void ratio_table(std::ostringstream& out, const std::vector<Row>& numerator, const std::vector<Row>& denominator,
                 const std::function<std::string(const std::string&, size_t)>& note) {
  const std::vector<size_t> counts = ordered_counts(numerator);
  header(out, "mesh \\ objects", counts);
  for (const std::string& mesh : ordered_meshes(numerator)) {
    out << "| " << mesh << " |";
    for (size_t c : counts) {
      out << " " << ratio_cell(find_row(numerator, mesh, c), find_row(denominator, mesh, c)) << note(mesh, c) << " |";
    }
    out << "\n";
  }
  out << "\n";
}

void speedup_table(std::ostringstream& out, const std::vector<Row>& sdf, const std::vector<Row>& tri,
                   const ThesisTables& thesis) {
  out << "### Speed-up of table 6.1 over table 6.3 (sdf-octree whitted FPS / tri-aabb shadow FPS)\n\n"
         "Measured here, the thesis' ratio in brackets (its \"<1\" entries taken as 1, so its ratio is a lower bound there).\n\n";
  ratio_table(out, sdf, tri, [&](const std::string& mesh, size_t c) -> std::string {
    const auto ta = thesis.find("6.1", mesh, c), tb = thesis.find("6.3", mesh, c);
    if (!ta || !tb) return "";
    return " (" + fixed(ta->fps / tb->fps, 0) + "x" + (tb->upper_bound ? "+" : "") + ")";
  });
}

// Two backends on the same device, in one mode: a's FPS / b's (above 1: a is faster); `what`
// says what the pair compares. Nothing when the rows lack either.
void pair_table(std::ostringstream& out, const std::string& mode, const std::vector<Row>& rows, const std::string& a,
                const std::string& b, const std::string& what) {
  std::vector<Row> as, bs;
  for (const Row& r : rows) {
    if (r.verdict().is_error()) continue;
    if (r["backend"] == a) as.push_back(r);
    if (r["backend"] == b) bs.push_back(r);
  }
  if (as.empty() || bs.empty()) return;
  out << "### " << a << " against " << b << " (" << what << "), " << mode << " mode (" << a << " FPS / " << b << " FPS, "
      << sizes_of(rows) << ")\n\n";
  ratio_table(out, as, bs, [](const std::string&, size_t) { return std::string(); });
}

void backends_table(std::ostringstream& out, const std::string& mode, const std::vector<Row>& rows) {
  std::vector<std::string> backends;
  for (const Row& r : rows)
    if (std::find(backends.begin(), backends.end(), r["backend"]) == backends.end()) backends.push_back(r["backend"]);
  out << "### Every backend, " << mode << " mode (" << sizes_of(rows) << "): FPS\n\n| mesh | objects |";
  for (const std::string& b : backends) out << " " << b << " |";
  out << "\n|---|---:|";
  for (size_t i = 0; i < backends.size(); ++i) out << "---:|";
  out << "\n";
  std::vector<std::pair<std::string, size_t>> keys;
  for (const Row& r : rows) {
    const std::pair<std::string, size_t> k{r["mesh"], static_cast<size_t>(r.number("objects"))};
    if (std::find(keys.begin(), keys.end(), k) == keys.end()) keys.push_back(k);
  }
  for (const auto& [mesh, objects] : keys) {
    out << "| " << mesh << " | " << objects << " |";
    for (const std::string& b : backends) {
      const Row* found = nullptr;
      for (const Row& r : rows)
        if (r["backend"] == b && r["mesh"] == mesh && static_cast<size_t>(r.number("objects")) == objects) found = &r;
      out << " " << (found ? fps_cell(*found) : "–") << " |";
    }
    out << "\n";
  }
  out << "\n";
}

// The overlap measured in the row's scene (CSV column overlap), "–" where none was.
std::string overlap_cell(const Row& r) { return r["overlap"].empty() ? "–" : fixed(r.number("overlap"), 1); }

// Adds `r` to the first group whose first row `same` accepts, or starts a group (file order kept).
template <class Same>
void add_to_group(std::vector<std::vector<Row>>& groups, const Row& r, Same same) {
  const auto it = std::find_if(groups.begin(), groups.end(), [&](const std::vector<Row>& g) { return same(g.front(), r); });
  if (it == groups.end()) groups.push_back({r});
  else it->push_back(r);
}

template <class T>
void add_once(std::vector<T>& list, const T& value) {
  if (std::find(list.begin(), list.end(), value) == list.end()) list.push_back(value);
}

const BackendInfo* registered(const std::string& name) {
  for (const BackendInfo& b : backends())
    if (b.name == name) return &b;
  return nullptr;  // a backend a CSV names that this sdfbench lacks (registered at run time elsewhere)
}

// Issue 37's question, from the registry's kinds: does a distance field (sdf-*) pass a hierarchy
// (a BVH in a compute kernel, the driver's ray tracing) on the same device?
bool is_field(const BackendInfo* b) { return b && b->vulkan && is_sdf(b->kind); }
bool is_hierarchy(const BackendInfo* b) { return b && b->vulkan && (b->kind == BackendKind::ComputeBvh || b->kind == BackendKind::DriverRt); }

// The overlap table's rows of one mesh, object count and mode: a row per k (asked, and the
// overlap measured in the scene), Mrays/s per backend, then each field's FPS over each hierarchy's.
void overlap_table(std::ostringstream& out, const std::vector<Row>& rows) {
  std::vector<std::string> names, ks;
  for (const Row& r : rows) {
    add_once(names, r["backend"]);
    add_once(ks, asked_overlap(r["scene"]));
  }
  std::vector<std::pair<std::string, std::string>> ratios;
  for (const std::string& a : names)
    for (const std::string& b : names)
      if (is_field(registered(a)) && is_hierarchy(registered(b))) ratios.emplace_back(a, b);
  const auto find = [&](const std::string& k, const std::string& backend) -> const Row* {
    for (const Row& r : rows)
      if (asked_overlap(r["scene"]) == k && r["backend"] == backend) return &r;
    return nullptr;
  };
  const Row& first = rows.front();
  out << "### Overlap: " << first["mesh"] << ", " << first["objects"] << " objects, " << first["mode"] << " mode (" << sizes_of(rows)
      << "): Mrays/s\n\nk: the scene's overlap as asked (`overlap:<mesh>:<count>:<k>`); overlap: as measured (instance boxes over "
         "a point of their union)";
  if (!ratios.empty()) out << "; a / b: a's FPS / b's (above 1: the distance field is faster)";
  out << ".\n\n| k | overlap |";
  for (const std::string& b : names) out << " " << b << " |";
  for (const auto& [a, b] : ratios) out << " " << a << " / " << b << " |";
  out << "\n|---:|---:|";
  for (size_t i = 0; i < names.size() + ratios.size(); ++i) out << "---:|";
  out << "\n";
  for (const std::string& k : ks) {
    std::string measured = "–";
    for (const Row& r : rows)
      if (asked_overlap(r["scene"]) == k && !r["overlap"].empty()) measured = overlap_cell(r);
    out << "| " << k << " | " << measured << " |";
    for (const std::string& b : names) {
      const Row* r = find(k, b);
      out << " " << (r ? speed_cell(*r, "mrays_per_s") : "–") << " |";
    }
    for (const auto& [a, b] : ratios) {
      const Row *ra = find(k, a), *rb = find(k, b);
      const bool failed = (ra && ra->verdict().is_error()) || (rb && rb->verdict().is_error());
      out << " " << (failed ? "–" : ratio_cell(ra, rb)) << " |";
    }
    out << "\n";
  }
  out << "\n";
}

// A sweep: the parameters that vary over its rows (renderers/backend_registry.h: any backend's),
// the structure's cost, the speed, the counters the backend has and the agreement (a sampled
// field's depth error also in voxels).
void sweep_table(std::ostringstream& out, const std::vector<Row>& rows) {
  std::vector<std::string> varying;
  for (const ParamSpec& spec : param_catalogue())
    if (std::any_of(rows.begin(), rows.end(), [&](const Row& r) { return r[spec.name] != rows.front()[spec.name]; }))
      varying.push_back(spec.name);
  struct Figure {
    const char *column, *title;
    int digits;
    double scale;
  };
  std::vector<Figure> figures = {{"build_ms", "build ms", 0, 1}, {"structure_bytes", "structure MB", 1, 1e-6}};
  std::vector<Figure> optional;  // the work counters (what the march evaluates, then the tests), the agreement
  for (CounterGroup group : {CounterGroup::evaluations, CounterGroup::tests})
    for (const CounterInfo& c : counter_table())
      if (c.group == group) optional.push_back({counter_columns()[c.id].c_str(), c.label, 1, 1});
  optional.insert(optional.end(), {{"tree_sah", "SAH cost", 1, 1},
                                   {"tree_epo", "EPO", 2, 1},
                                   {"tree_nodes", "BVH nodes", 0, 1},
                                   {"hit_agreement", "hit %", 2, 1},
                                   {"id_agreement", "id %", 2, 1},
                                   {"depth_p99_voxels", "depth p99 (voxels)", 3, 1},
                                   {"psnr", "PSNR dB", 1, 1}});
  for (const Figure& f : optional)
    if (std::any_of(rows.begin(), rows.end(), [&](const Row& r) { return !r[f.column].empty(); })) figures.push_back(f);
  // sweep --overlap: the scene's k (asked, and the overlap measured) is an axis too
  const bool over_k = std::any_of(rows.begin(), rows.end(), [&](const Row& r) { return r["scene"] != rows.front()["scene"]; });
  out << "### Sweep: " << overlap_family(rows.front()["scene"]) << ", " << rows.front()["backend"] << ", " << rows.front()["mode"]
      << " (" << sizes_of(rows) << ")\n\n|";
  if (over_k) out << " k | overlap |";
  for (const std::string& name : varying) out << " " << name << " |";
  out << " FPS | Mrays/s |";
  for (const Figure& f : figures) out << " " << f.title << " |";
  out << "\n|";
  if (over_k) out << "---:|---:|";
  for (size_t i = 0; i < varying.size(); ++i) out << "---|";
  for (size_t i = 0; i < figures.size() + 2; ++i) out << "---:|";
  out << "\n";
  for (const Row& r : rows) {
    out << "|";
    if (over_k) out << " " << asked_overlap(r["scene"]) << " | " << overlap_cell(r) << " |";
    for (const std::string& name : varying) out << " " << (r[name].empty() ? "–" : r[name]) << " |";
    out << " " << fps_cell(r) << " | " << fixed(r.number("mrays_per_s"), 3) << " |";
    for (const Figure& f : figures)
      out << " " << (r[f.column].empty() ? std::string("–") : fixed(r.number(f.column) * f.scale, f.digits)) << " |";
    out << "\n";
  }
  out << "\n";
}

}  // namespace

std::string markdown_report(const CsvTable& csv, const ThesisTables& thesis) {
  const std::vector<Row> rows = rows_of(csv);
  std::ostringstream out;
  std::map<std::string, std::vector<Row>> by_table, by_mode;
  std::vector<std::vector<Row>> sweeps;  // one table per scene (its every k), backend and mode (merged sweeps), in file order
  std::vector<std::vector<Row>> overlaps;  // one table per mesh, object count and mode, in file order
  for (const Row& r : rows) {
    if (r["table"] == kOverlapTable) {
      add_to_group(overlaps, r, [](const Row& a, const Row& b) {
        return a["mesh"] == b["mesh"] && a["objects"] == b["objects"] && a["mode"] == b["mode"];
      });
      continue;
    }
    if (r["table"] == "sweep") {
      add_to_group(sweeps, r, [](const Row& a, const Row& b) {
        return overlap_family(a["scene"]) == overlap_family(b["scene"]) && a["backend"] == b["backend"] && a["mode"] == b["mode"];
      });
      continue;
    }
    if (!r["table"].empty()) by_table[r["table"]].push_back(r);
    by_mode[r["mode"]].push_back(r);
  }
  for (const ThesisTableConfig& config : thesis_table_configs())
    if (by_table.count(config.id)) thesis_table(out, config, by_table[config.id], thesis);
  if (by_table.count("6.1") && by_table.count("6.3")) speedup_table(out, by_table["6.1"], by_table["6.3"], thesis);
  for (const auto& [mode, mode_rows] : by_mode) {
    backends_table(out, mode, mode_rows);
    for (const BackendInfo& backend : backends())  // the pairs each backend declares (renderers/backend_registry.h)
      for (const BackendPartner& partner : backend.partners) pair_table(out, mode, mode_rows, backend.name, partner.other, partner.what);
  }
  for (const std::vector<Row>& overlap : overlaps) overlap_table(out, overlap);
  for (const std::vector<Row>& sweep : sweeps) sweep_table(out, sweep);
  if (rows.empty()) out << "(no measurements)\n";
  // Every mark a row can get here (≠ is the HTML report's: it re-renders rows).
  std::vector<VerdictMark> failures, cautions;
  for (const VerdictMark& m : all_verdict_marks())
    if (m.kind != Mark::not_reproduced) (m.failure ? failures : cautions).push_back(m);
  out << "Flags, the row failed what it promised: " << verdict_legend(failures) << ". Cautions: " << verdict_legend(cautions)
      << ".\n";
  return out.str();
}

}  // namespace sdfbench
