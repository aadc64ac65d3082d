#include "harness/benchmark_json.h"

#include <charconv>
#include <cmath>
#include <ctime>
#include <map>
#include <thread>

#include <nlohmann/json.hpp>
#include <unistd.h>

#include "harness/measurement.h"

namespace sdfbench {
namespace {

// The numeric columns that become counters (when the row has a finite value), the work counters' among them.
const std::vector<std::string>& counter_fields() {
  static const std::vector<std::string> fields = [] {
    std::vector<std::string> f = {"mrays_per_s", "fps", "rays_per_pixel"};
    f.insert(f.end(), counter_columns().begin(), counter_columns().end());
    f.insert(f.end(), {"prepare_ms", "build_ms", "structure_bytes", "tree_sah", "tree_epo", "tree_nodes", "hit_agreement", "id_agreement", "psnr", "depth_p99",
                       "depth_p99_voxels", "overlap", "frames", "load_avg", "cpu_steal_pct"});
    return f;
  }();
  return fields;
}

bool number(const std::string& text, double& value) {
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return !text.empty() && ec == std::errc() && end == text.data() + text.size() && std::isfinite(value);
}

std::string field(const CsvTable& rows, size_t row, const char* column) {
  return rows.has_column(column) ? rows.rows[row][rows.column(column)] : std::string();
}

}  // namespace

std::string benchmark_json(const CsvTable& rows) {
  // Beyond scene/backend/mode/size, the key columns whose values differ between rows of the same
  // backend name them (another backend's parameters are empty in its rows, and name nothing).
  const size_t backend_column = rows.column("backend");
  std::map<std::string, std::vector<size_t>> varying;  // by backend
  for (const std::string& name : configuration_key_columns()) {
    if (!rows.has_column(name) || name == "scene" || name == "backend" || name == "mode" || name == "width" || name == "height")
      continue;
    const size_t c = rows.column(name);
    std::map<std::string, const std::string*> first;  // each backend's first value
    for (const auto& row : rows.rows) {
      const auto [at, fresh] = first.emplace(row[backend_column], &row[c]);
      std::vector<size_t>& of_backend = varying[row[backend_column]];
      if (!fresh && *at->second != row[c] && (of_backend.empty() || of_backend.back() != c)) of_backend.push_back(c);
    }
  }
  nlohmann::ordered_json doc;
  char host[256] = {};
  gethostname(host, sizeof host - 1);
  auto& context = doc["context"];
  char date[32] = {};
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  std::strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", &utc);
  context["date"] = date;
  context["host_name"] = host;
  context["executable"] = "sdfbench";
  context["num_cpus"] = std::thread::hardware_concurrency();
  context["mhz_per_cpu"] = 0;
  context["cpu_scaling_enabled"] = false;
  context["caches"] = nlohmann::ordered_json::array();
  context["library_build_type"] = "release";
  for (const char* c : {"device", "driver", "cpu", "threads", "embree", "commit", "run_id"})
    if (!rows.rows.empty()) context[std::string("sdfbench_") + c] = field(rows, 0, c);
  auto& benchmarks = doc["benchmarks"] = nlohmann::ordered_json::array();
  for (size_t r = 0; r < rows.rows.size(); ++r) {
    std::string name = field(rows, r, "scene") + "/" + field(rows, r, "backend") + "/" + field(rows, r, "mode") + "/" +
                       field(rows, r, "width") + "x" + field(rows, r, "height");
    for (size_t c : varying[rows.rows[r][backend_column]]) name += "/" + rows.columns[c] + ":" + rows.rows[r][c];
    nlohmann::ordered_json b;
    b["name"] = name;
    b["family_index"] = r;
    b["per_family_instance_index"] = 0;
    b["run_name"] = name;
    b["run_type"] = "iteration";
    b["repetitions"] = 1;
    b["repetition_index"] = 0;
    b["threads"] = 1;
    double ms = 0.0, frames = 0.0;
    if (!number(field(rows, r, "ms_median"), ms)) {
      b["error_occurred"] = true;
      b["error_message"] = field(rows, r, "agreement");
      benchmarks.push_back(std::move(b));
      continue;
    }
    b["iterations"] = number(field(rows, r, "frames"), frames) ? static_cast<uint64_t>(frames) : 0;
    b["real_time"] = ms;
    b["cpu_time"] = ms;  // no CPU time is measured (see the header)
    b["time_unit"] = "ms";
    for (const std::string& counter : counter_fields())
      if (double v = 0.0; number(field(rows, r, counter.c_str()), v)) b[counter] = v;
    b["agreement"] = field(rows, r, "agreement");
    benchmarks.push_back(std::move(b));
  }
  return doc.dump(2) + "\n";
}

}  // namespace sdfbench
