#include "harness/html_report.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <sstream>

#include "harness/measurement.h"
#include "harness/row_verdict.h"
#include "harness/structure_winners.h"

namespace sdfbench {
namespace {

std::string escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

// A path as an href: each byte outside the unreserved set and '/' percent-encoded.
std::string href(const std::string& path) {
  static const char* hex = "0123456789ABCDEF";
  std::string out;
  for (unsigned char c : path) {
    if (std::isalnum(c) || c == '/' || c == '.' || c == '-' || c == '_' || c == '~') out += static_cast<char>(c);
    else out += {'%', hex[c >> 4], hex[c & 15]};
  }
  return out;
}

std::string fixed(double v, int digits) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", digits, v);
  return text;
}

// A speed ratio with two decimals, or two significant digits below 0.01 (a 500x slower tracer
// reads 0.0020x, not 0.00x).
std::string ratio_text(double ratio) {
  const int digits = ratio > 0 && ratio < 0.01 ? std::min(6, 1 - int(std::floor(std::log10(ratio)))) : 2;
  return fixed(ratio, digits);
}

std::string fps_text(double fps) { return fixed(fps, fps >= 100 ? 0 : fps >= 10 ? 1 : fps >= 1 ? 2 : 3); }

// A row read by column name; a column an older CSV lacks reads as empty.
struct Row {
  const CsvTable* table;
  size_t index;
  const std::string& operator[](const std::string& column) const {
    static const std::string none;
    return table->has_column(column) ? table->rows[index][table->column(column)] : none;
  }
  double number(const std::string& column) const { return std::atof((*this)[column].c_str()); }
};

// The row's verdict (harness/row_verdict.h), ≠ when its re-rendered images are not the row's.
RowVerdict verdict_of(const Row& r, const RowImages& images) {
  return row_verdict(*r.table, r.table->rows[r.index], images.mismatch);
}

// The FPS and the row's marks; an ERROR row has no FPS, its mark stands in for it.
std::string fps_cell(const Row& r, const RowVerdict& verdict) {
  if (verdict.is_error()) return verdict.symbols();
  const std::string fps = fps_text(r.number("fps"));
  return verdict.marks.empty() ? fps : fps + " " + verdict.symbols();
}

// A flagged row's colour: red when it failed what it promised, yellow for a caution.
const char* row_class(const RowVerdict& v) {
  return v.is_failure() ? "bad" : v.is_approximate() ? "approx" : v.is_caution() ? "warn" : "";
}

std::string distinct(const CsvTable& t, const std::string& column) {
  if (!t.has_column(column)) return "(not recorded)";
  std::vector<std::string> values;
  for (const auto& row : t.rows) {
    const std::string& v = row[t.column(column)];
    if (!v.empty() && std::find(values.begin(), values.end(), v) == values.end()) values.push_back(v);
  }
  std::string text;
  for (size_t i = 0; i < values.size() && i < 6; ++i) text += (i ? ", " : "") + values[i];
  if (values.size() > 6) text += ", ... (" + std::to_string(values.size()) + " values)";
  return text.empty() ? "–" : text;
}

std::string sizes_of(const CsvTable& t, const std::vector<size_t>& rows) {
  std::set<std::string> sizes;
  for (size_t i : rows) sizes.insert(Row{&t, i}["width"] + "x" + Row{&t, i}["height"]);
  std::string text;
  for (const std::string& s : sizes) text += (text.empty() ? "" : ", ") + s;
  return text;
}

std::string load_summary(const CsvTable& t) {
  if (!t.has_column("load_avg")) return "not recorded (a CSV from before the load columns)";
  double lo = 1e30, hi = 0, steal = 0, other = 0;
  size_t measured = 0, busy = 0;
  for (size_t i = 0; i < t.rows.size(); ++i) {
    const Row r{&t, i};
    if (r["load_avg"].empty()) continue;
    ++measured;
    lo = std::min(lo, r.number("load_avg"));
    hi = std::max(hi, r.number("load_avg"));
    steal = std::max(steal, r.number("cpu_steal_pct"));
    other = std::max(other, r.number("cpu_other_pct"));
    busy += r["busy"] == "1";
  }
  if (!measured) return "not measured";
  return "load average " + fixed(lo, 2) + "–" + fixed(hi, 2) + ", CPU steal up to " + fixed(steal, 1) +
         " %, other processes up to " + fixed(other, 1) + " % of the CPUs; " + std::to_string(busy) + " of " +
         std::to_string(measured) + " rows timed on a busy machine (‡)";
}

void environment(std::ostringstream& out, const ReportFile& file) {
  const CsvTable& t = file.table;
  out << "<table class=\"env\">\n";
  auto line = [&](const std::string& name, const std::string& value) {
    out << "<tr><th>" << escape(name) << "</th><td>" << escape(value) << "</td></tr>\n";
  };
  line("rows", std::to_string(t.rows.size()));
  line("device", distinct(t, "device"));
  line("driver", distinct(t, "driver"));
  line("CPU", distinct(t, "cpu"));
  line("threads", distinct(t, "threads"));
  line("Embree", distinct(t, "embree"));
  line("commit", distinct(t, "commit"));
  line("modes", distinct(t, "mode"));
  std::vector<size_t> all(t.rows.size());
  for (size_t i = 0; i < all.size(); ++i) all[i] = i;
  line("frame size", sizes_of(t, all));
  line("check size (agreement)", distinct(t, "check_size") + " against " + distinct(t, "reference"));
  line("frames", distinct(t, "requested_frames") + " timed after " + distinct(t, "warmup") + " warm-up, clock " + distinct(t, "clock"));
  line("machine load", load_summary(t));
  out << "</table>\n";
}

// (appended, not "f" + std::to_string(...): GCC 12 gives a false -Wrestrict there, GCC bug 105651)
std::string anchor(size_t file, size_t row) { return std::string("f").append(std::to_string(file)).append("r").append(std::to_string(row)); }

void thesis_tables(std::ostringstream& out, const std::vector<ReportFile>& files, const ThesisTables& thesis) {
  bool any = false;
  for (size_t f = 0; f < files.size(); ++f) {
    const CsvTable& t = files[f].table;
    for (const ThesisTableConfig& config : thesis_table_configs()) {
      std::vector<size_t> rows;
      for (size_t i = 0; i < t.rows.size(); ++i)
        if (Row{&t, i}["table"] == config.id) rows.push_back(i);
      if (rows.empty()) continue;
      if (!any) out << "<h2 id=\"thesis\">The thesis' tables</h2>\n";
      any = true;
      std::vector<std::string> meshes;
      std::set<size_t> counts;
      for (size_t i : rows) {
        const Row r{&t, i};
        if (std::find(meshes.begin(), meshes.end(), r["mesh"]) == meshes.end()) meshes.push_back(r["mesh"]);
        counts.insert(static_cast<size_t>(r.number("objects")));
      }
      const std::string sizes = sizes_of(t, rows);
      out << "<h3>Table " << config.id << ": " << escape(config.backend) << ", " << to_string(config.mode) << " ("
          << escape(t.source) << ")</h3>\n<p>" << escape(config.description) << ". Each cell: FPS measured here ("
          << escape(distinct(t, "device")) << ", " << escape(sizes) << "), the thesis' FPS (GTX 1070, 1280x720) and ours / the thesis'."
          << (sizes != "1280x720" ? " <strong>Other resolution than the thesis': FPS are not comparable, only the trends.</strong>" : "")
          << " Another device than the thesis' GPU: the ratio says how far this device is, not the method.</p>\n"
          << "<table class=\"grid\"><tr><th>mesh \\ objects</th>";
      for (size_t c : counts) out << "<th>" << c << "</th>";
      out << "</tr>\n";
      for (const std::string& mesh : meshes) {
        out << "<tr><th>" << escape(mesh) << "</th>";
        for (size_t c : counts) {
          const size_t* found = nullptr;
          for (const size_t& i : rows)
            if (Row{&t, i}["mesh"] == mesh && static_cast<size_t>(Row{&t, i}.number("objects")) == c) found = &i;
          if (!found) { out << "<td>–</td>"; continue; }
          const Row r{&t, *found};
          const RowVerdict verdict = verdict_of(r, files[f].images[*found]);
          const std::optional<ThesisValue> v = thesis.find(config.id, mesh, c);
          const double fps = r.number("fps");
          out << "<td class=\"" << row_class(verdict) << "\"><a href=\"#" << anchor(f, *found) << "\"><b>"
              << fps_cell(r, verdict) << "</b></a>";
          if (v) {
            out << "<br><span class=\"thesis\">thesis " << (v->upper_bound ? "&lt;1" : fps_text(v->fps)) << "</span><br>"
                << (v->upper_bound ? "&gt;" : "") << fixed(fps / v->fps, fps / v->fps >= 10 ? 0 : 2) << "x the thesis'";
          }
          out << "</td>";
        }
        out << "</tr>\n";
      }
      out << "</table>\n";
    }
  }
}

std::string cell(const Row& r, const std::string& column, int digits) {
  return r[column].empty() ? "–" : r[column] == "inf" ? "∞" : fixed(r.number(column), digits);
}

// The answer first: per file, scene, mode and size, the fastest row of each kind of method with
// its ratio to the group's winner, memory, build time and verdict (harness/structure_winners.h).
void winners_section(std::ostringstream& out, const std::vector<ReportFile>& files) {
  std::vector<const CsvTable*> tables;
  for (const ReportFile& f : files) tables.push_back(&f.table);
  const StructureWinners winners = structure_winners(tables, [&](size_t f, size_t row) {
    return verdict_of(Row{&files[f].table, row}, files[f].images[row]);
  });
  const auto kinds_present = [](const WinnerGroup& g) {
    return std::count_if(g.best.begin(), g.best.end(), [](const auto& b) { return b.has_value(); });
  };
  out << "<h2 id=\"wins\">Which structure wins where</h2>\n<p>Rows of one file that measured the same scene, mode and "
         "frame size, side by side: for each kind of method its fastest configuration, with Mrays/s, its speed as a "
         "fraction of the group's winner (the winner: its margin over the next kind), structure MB and build seconds; "
         "where the winner runs on the CPU (Embree), the fastest kind on the Vulkan device is named too. "
         "Rows that failed what they promised (red) are left out and counted; field hits (≈) are approximations, "
         "shown in their own kind and never the winner. Speeds compare only within a group: each group is one file, "
         "one machine.</p>\n";
  bool any = false;
  for (size_t f = 0; f < files.size(); ++f) {
    std::vector<const WinnerGroup*> groups;
    for (const WinnerGroup& g : winners.groups)
      if (g.file == f && kinds_present(g) >= 2) groups.push_back(&g);
    if (groups.empty()) continue;
    any = true;
    const CsvTable& t = files[f].table;
    std::vector<size_t> columns;  // the kinds this file's groups have
    for (size_t k = 0; k < winners.kinds.size(); ++k)
      if (std::any_of(groups.begin(), groups.end(), [&](const WinnerGroup* g) { return g->best[k].has_value(); }))
        columns.push_back(k);
    out << "<h3><a href=\"#file" << f << "\">" << escape(t.source) << "</a></h3>\n<table class=\"wins\"><tr><th>scene</th><th>mode</th><th>size</th>";
    for (size_t k : columns) out << "<th>" << escape(winners.kinds[k]) << "</th>";
    out << "</tr>\n";
    for (const WinnerGroup* g : groups) {
      const auto speed = [&](size_t row) { return Row{&t, row}.number("mrays_per_s"); };
      const double top = g->winner ? speed(*g->best[*g->winner]) : 0;
      const double next = g->runner_up ? speed(*g->best[*g->runner_up]) : 0;
      out << "<tr><th>" << escape(g->scene) << (g->overlap.empty() ? "" : "<br><span class=\"param\">overlap " + escape(g->overlap) + "</span>")
          << (g->failed ? "<br><span class=\"why\">" + std::to_string(g->failed) + " failed row(s) left out</span>" : "")
          << "</th><td>" << escape(g->mode) << "</td><td>" << escape(g->size) << "</td>";
      for (size_t k : columns) {
        if (!g->best[k]) { out << "<td>–</td>"; continue; }
        const size_t row = *g->best[k];
        const Row r{&t, row};
        const RowVerdict verdict = verdict_of(r, files[f].images[row]);
        const bool won = g->winner == k;
        const double v = speed(row);
        // (streamed, not concatenated: GCC 12 gives a false -Wrestrict on "<literal>" + std::string, GCC bug 105651)
        std::ostringstream ratio;
        if (won) ratio << "winner" << (next > 0 ? ", " + fixed(v / next, 2) + "x the next" : std::string());
        else if (top > 0) ratio << ratio_text(v / top) << "x the winner";
        if (!won && g->vulkan_winner == k) ratio << "; fastest on the Vulkan device";
        out << "<td class=\"" << (won ? "win" : row_class(verdict)) << "\"><a href=\"#" << anchor(f, row) << "\">"
            << (won ? "<b>" : "") << escape(r["backend"]) << (won ? "</b>" : "") << "</a> " << cell(r, "mrays_per_s", 3)
            << " Mrays/s" << (verdict.marks.empty() ? "" : " ") << verdict.symbols() << "<br>" << ratio.str();
        if (!r["structure_bytes"].empty()) out << "<br>" << fixed(r.number("structure_bytes") / 1e6, 1) << " MB";
        if (!r["build_ms"].empty()) out << (r["structure_bytes"].empty() ? "<br>" : ", ") << fixed(r.number("build_ms") / 1e3, 2) << " s build";
        if (verdict.approximate_voxels) out << "<br>depth error " << fixed(*verdict.approximate_voxels, 2) << " voxels";
        out << "</td>";
      }
      out << "</tr>\n";
    }
    out << "</table>\n";
  }
  if (!any) out << "<p>No run here measured two kinds of method on one scene.</p>\n";
}

// Key columns (beyond scene, backend, mode and size) whose values differ between the file's rows:
// a sweep's axes, a table's per-backend settings.
std::vector<std::string> varying_columns(const CsvTable& t) {
  static const std::set<std::string> shown = {"table", "scene", "backend", "mode", "width", "height"};
  std::vector<std::string> varying;
  for (const std::string& name : configuration_key_columns()) {
    if (shown.count(name) || !t.has_column(name)) continue;
    std::set<std::string> values;  // an empty field is a column of another backend's family
    for (const auto& row : t.rows)
      if (!row[t.column(name)].empty()) values.insert(row[t.column(name)]);
    if (values.size() > 1) varying.push_back(name);
  }
  return varying;
}

void thumbnail(std::ostringstream& out, const std::string& path, const std::string& what, const Row& r) {
  const std::string alt = what + ": " + r["scene"] + ", " + r["backend"] + ", " + r["mode"];
  out << "<a href=\"" << href(path) << "\"><img src=\"" << href(path) << "\" width=\"128\" alt=\"" << escape(alt) << "\" title=\""
      << escape(what) << "\"></a>";
}

void rows_table(std::ostringstream& out, const ReportFile& file, size_t f) {
  const CsvTable& t = file.table;
  const std::vector<std::string> varying = varying_columns(t);
  out << "<table class=\"rows\"><tr><th>#</th><th>configuration</th><th>FPS</th><th>Mrays/s</th><th>build ms</th><th>MB</th>"
         "<th>hit %</th><th>id %</th><th>depth p99</th><th>PSNR dB</th><th>agreement</th><th>load</th>"
         "<th>frame · reference · difference</th></tr>\n";
  for (size_t i = 0; i < t.rows.size(); ++i) {
    const Row r{&t, i};
    const RowImages& images = file.images[i];
    const RowVerdict verdict = verdict_of(r, images);
    out << "<tr id=\"" << anchor(f, i) << "\" class=\"" << row_class(verdict) << "\"><td>"
        << escape(r["run_index"]) << "</td><td><b>" << escape(r["backend"]) << "</b> " << escape(r["mode"]) << "<br>"
        << escape(r["scene"]) << ", " << escape(r["width"]) << "x" << escape(r["height"])
        << (r["table"].empty() ? "" : ", table " + escape(r["table"]));
    for (const std::string& name : varying)
      if (!r[name].empty()) out << "<br><span class=\"param\">" << escape(name) << "=" << escape(r[name]) << "</span>";
    if (!r["backend_resolved"].empty()) out << "<br><span class=\"param\">" << escape(r["backend_resolved"]) << "</span>";
    const std::string voxels = r["depth_p99_voxels"].empty() ? "" : "<br>" + cell(r, "depth_p99_voxels", 3) + " voxels";
    out << "</td><td>" << fps_cell(r, verdict) << "</td><td>" << cell(r, "mrays_per_s", 3) << "</td><td>"
        << cell(r, "build_ms", 0) << "</td><td>"
        << (r["structure_bytes"].empty() ? "–" : fixed(r.number("structure_bytes") / 1e6, 1))
        << (r["tree_sah"].empty() ? "" : "<br>SAH " + cell(r, "tree_sah", 1) + "<br>EPO " + cell(r, "tree_epo", 2) + "<br>" +
                                             cell(r, "tree_nodes", 0) + " nodes")
        << "</td><td>" << cell(r, "hit_agreement", 2) << "</td><td>" << cell(r, "id_agreement", 2) << "</td><td>"
        << (r["depth_p99"].empty() ? "–" : escape(r["depth_p99"])) << voxels << "</td><td>" << cell(r, "psnr", 1) << "</td><td>"
        << escape(r["agreement"])
        << (verdict.marks.empty() ? "" : "<br><span class=\"why\">" + escape(verdict.reasons()) + "</span>")
        << "</td><td>" << (r["load_avg"].empty() ? "–" : cell(r, "load_avg", 2) + "<br>steal " + cell(r, "cpu_steal_pct", 1) +
                                                             " %<br>other " + cell(r, "cpu_other_pct", 1) + " %")
        << "</td><td class=\"images\">";
    if (!images.frame.empty()) {
      thumbnail(out, images.frame, r["backend"] + "'s frame", r);
      thumbnail(out, images.reference, "the reference's frame (" + r["reference"] + ")", r);
      thumbnail(out, images.diff, "difference map", r);
    }
    if (!images.note.empty()) out << "<br><span class=\"note\">" << escape(images.note) << "</span>";
    out << "</td></tr>\n";
  }
  out << "</table>\n";
}

const char* kStyle = R"(body{font:14px/1.4 system-ui,sans-serif;margin:1.5em;color:#222}
h1{margin-top:0}h2{border-bottom:1px solid #ccc;padding-bottom:.2em;margin-top:1.6em}
table{border-collapse:collapse;margin:.6em 0}th,td{border:1px solid #ddd;padding:3px 6px;vertical-align:top}
th{background:#f3f3f3;text-align:left}table.env th{width:13em}table.grid td{text-align:right;min-width:6em}
table.rows td:nth-child(n+3):nth-child(-n+10){text-align:right}
tr.bad,td.bad,li.bad{background:#fbe0e0}tr.warn,td.warn,li.warn{background:#fff6d6}
tr.approx,td.approx,li.approx{background:#e6f0fb}td.win{background:#e3f5e1}table.wins td{min-width:9em}
.thesis,.param,.note,.why{color:#666;font-size:12px}.why{color:#a00}
td.images{white-space:nowrap}td.images img{margin-right:3px;border:1px solid #999;image-rendering:auto}
figure{display:inline-block;margin:0 1em 1em 0;vertical-align:top}figure img{max-width:640px;border:1px solid #ccc}
figcaption{font-size:12px;color:#555})";

}  // namespace

std::string html_report(const std::vector<ReportFile>& files, const std::vector<ReportPlot>& plots, const ThesisTables& thesis,
                        const std::string& generator) {
  std::ostringstream out;
  out << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>sdfbench report</title>\n<style>" << kStyle
      << "</style></head><body>\n<h1>sdfbench report</h1>\n<p>Written by sdfbench " << escape(generator) << " from ";
  for (size_t f = 0; f < files.size(); ++f) out << (f ? ", " : "") << "<a href=\"#file" << f << "\">" << escape(files[f].table.source) << "</a>";
  out << ". Every row's images were checked against the reference backend at the check size before its figures were "
         "reported; the thumbnails are those check images (click for full size). The difference map is each pixel's "
         "largest channel error, dark violet 0 to yellow 0.1 and above (the check counts a pixel failed from 0.05).</p>\n";
  std::vector<VerdictMark> failures, approximations, cautions;
  for (const VerdictMark& m : all_verdict_marks())
    (m.failure ? failures : m.kind == Mark::approximate ? approximations : cautions).push_back(m);
  out << "<p>Flags: " << escape(verdict_legend(failures)) << " (<span class=\"bad\">red rows</span>: the row failed what it "
      << "promised); " << escape(verdict_legend(approximations)) << " (<span class=\"approx\">blue rows</span>); "
      << escape(verdict_legend(cautions)) << " (<span class=\"warn\">yellow rows</span>).</p>\n"
      << "<p><a href=\"#wins\">Which structure wins where</a> · <a href=\"#thesis\">the thesis' tables</a> · "
         "<a href=\"#flagged\">flagged rows</a> · <a href=\"#plots\">plots</a> · every file's rows below.</p>\n";
  winners_section(out, files);
  thesis_tables(out, files, thesis);
  // Flagged rows in three lists: failures (red), approximations (≈, blue), cautions (yellow).
  std::ostringstream lists[3];
  size_t counts[3] = {0, 0, 0};
  for (size_t f = 0; f < files.size(); ++f)
    for (size_t i = 0; i < files[f].table.rows.size(); ++i) {
      const Row r{&files[f].table, i};
      const RowVerdict verdict = verdict_of(r, files[f].images[i]);
      if (verdict.marks.empty()) continue;
      const size_t list = verdict.is_failure() ? 0 : verdict.is_approximate() ? 1 : 2;
      ++counts[list];
      lists[list] << "<li class=\"" << row_class(verdict) << "\"><a href=\"#" << anchor(f, i) << "\">"
                  << escape(files[f].table.source) << " #" << escape(r["run_index"]) << "</a> " << escape(r["backend"]) << " "
                  << escape(r["mode"]) << " " << escape(r["scene"]) << ": " << verdict.symbols() << " "
                  << escape(verdict.reasons()) << "</li>\n";
    }
  out << "<h2 id=\"flagged\">Flagged rows</h2>\n";
  const char* titles[3] = {"Failed what they promised", "Approximations: field hits", "Cautions"};
  for (size_t l = 0; l < 3; ++l) {
    out << "<h3>" << titles[l] << " (" << counts[l] << ")</h3>\n";
    if (counts[l]) out << "<ul>\n" << lists[l].str() << "</ul>\n";
    else out << "<p>None.</p>\n";
  }
  if (!plots.empty()) {
    out << "<h2 id=\"plots\">Plots</h2>\n";
    for (const ReportPlot& p : plots)
      out << "<figure><a href=\"" << href(p.href) << "\"><img src=\"" << href(p.href) << "\" alt=\"" << escape(p.caption)
          << "\"></a><figcaption>" << escape(p.caption) << "</figcaption></figure>\n";
  }
  for (size_t f = 0; f < files.size(); ++f) {
    out << "<h2 id=\"file" << f << "\">" << escape(files[f].table.source) << "</h2>\n";
    environment(out, files[f]);
    rows_table(out, files[f], f);
  }
  out << "</body></html>\n";
  return out.str();
}

}  // namespace sdfbench
