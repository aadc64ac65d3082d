#include "harness/row_rerender.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "harness/image_output.h"
#include "harness/measurement.h"
#include "harness/row_configuration.h"
#include "harness/system_info.h"

namespace sdfbench {

namespace fs = std::filesystem;

namespace {

// A CSV as its real path: x.csv and ./x.csv are one file of the list.
std::string real_path(const std::string& path) {
  std::error_code ec;
  const fs::path real = fs::weakly_canonical(path, ec);
  return ec ? path : real.string();
}

const std::vector<std::string> kListColumns = {"csv", "key", "frame", "reference", "diff", "sdfbench", "reference_row",
                                                "hit_agreement", "id_agreement", "psnr", "depth_p99", "depth_p99_voxels"};

std::string figure(const std::optional<double>& v) { return v ? csv_number(*v) : ""; }

double value(const std::string& text) { return text == "inf" ? INFINITY : std::strtod(text.c_str(), nullptr); }

}  // namespace

std::string rerender_differences(const CsvTable& t, size_t row, const Rerender& r) {
  if (r.reference_row) return "";
  const RowConfiguration rc = row_configuration(t, row);
  const double half_pixel = 50.0 / (static_cast<double>(rc.check_size.width) * rc.check_size.height);  // % of the image
  std::string differences;
  auto check = [&](const char* column, const std::string& ours, auto&& close) {
    if (!t.has_column(column)) return;  // an older CSV: the figure was not recorded
    const std::string& theirs = t.rows[row][t.column(column)];
    if (theirs == ours || (!theirs.empty() && !ours.empty() && close(value(theirs), value(ours)))) return;
    differences += std::string(differences.empty() ? "" : ", ") + column + " " + (theirs.empty() ? "–" : theirs) + " → " +
                   (ours.empty() ? "–" : ours);
  };
  check("hit_agreement", r.hit_agreement, [&](double a, double b) { return std::abs(a - b) < half_pixel; });
  check("id_agreement", r.id_agreement, [&](double a, double b) { return std::abs(a - b) < half_pixel; });
  check("psnr", r.psnr, [](double a, double b) { return (a >= 100 && b >= 100) || std::abs(a - b) <= 0.01; });
  check("depth_p99", r.depth_p99, [](double a, double b) { return std::abs(a - b) <= 1e-3 * std::max(std::abs(a), std::abs(b)) + 1e-12; });
  check("depth_p99_voxels", r.depth_p99_voxels, [](double a, double b) { return std::abs(a - b) <= 1e-3; });
  return differences;
}

RowRerenderer::RowRerenderer(ImageStore& store, fs::path dir, std::string device)
    : store_(store), dir_(std::move(dir)), device_(std::move(device)) {
  list_.columns = kListColumns;
  if (fs::exists(dir_ / kListName)) {
    CsvTable old = read_csv(dir_ / kListName);
    if (old.columns == kListColumns) previous_ = std::move(old);  // another layout: rendered again
  }
}

const std::vector<std::string>* RowRerenderer::find_listed(const CsvTable& t, size_t row) const {
  const std::string key = configuration_key(t.rows[row], t.columns);
  for (const auto& line : previous_.rows) {
    if (line[0] != real_path(t.source) || line[1] != key) continue;
    for (int i = 2; i <= 4; ++i)
      if (const fs::path file = store_.file_of(line[i]); file.empty() || !fs::exists(file)) return nullptr;
    return &line;
  }
  return nullptr;
}

Rerender RowRerenderer::get(const CsvTable& t, size_t row) {
  if (const std::vector<std::string>* found = find_listed(t, row)) {
    const std::vector<std::string>& line = *found;
    Rerender r{store_.add_file(store_.file_of(line[2]), "rendered image"), store_.add_file(store_.file_of(line[3]), "rendered image"),
               store_.add_file(store_.file_of(line[4]), "rendered image"), line[5], line[6] == "1", line[7], line[8], line[9],
               line[10], line[11]};
    list_.rows.push_back(line);
    return r;
  }
  const std::string key = configuration_key(t.rows[row], t.columns);
  const Rerender r = render(t, row);
  list_.rows.push_back({real_path(t.source), key, r.frame, r.reference, r.diff, r.sdfbench, r.reference_row ? "1" : "0", r.hit_agreement,
                        r.id_agreement, r.psnr, r.depth_p99, r.depth_p99_voxels});
  write_list(true);
  return r;
}

Rerender RowRerenderer::render(const CsvTable& t, size_t row) {
  RowConfiguration rc = row_configuration(t, row);
  if (!device_.empty()) rc.config.options.device = device_;
  const std::string key = rc.reference + " " + std::to_string(rc.check_size.width) + "x" + std::to_string(rc.check_size.height);
  auto it = runners_.find(key);
  if (it == runners_.end()) {
    BenchSettings settings;
    settings.reference = rc.reference;
    settings.check_size = rc.check_size;
    it = runners_.emplace(key, std::make_unique<BenchmarkRunner>(settings)).first;
  }
  const CheckedFrame checked = it->second->check_frame(rc.config);
  const Agreement& g = checked.agreement;
  return {store_.add(color_image(checked.frame)), store_.add(color_image(checked.reference)),
          store_.add(difference_map(checked.frame, checked.reference)), git_commit(), rc.config.backend == rc.reference,
          figure(g.hit_percent), figure(g.id_percent), figure(g.psnr), figure(g.depth_p99), figure(g.depth_p99_voxels)};
}

void RowRerenderer::write_list(bool keep_unreached) const {
  CsvTable out = list_;
  if (keep_unreached)
    for (const auto& line : previous_.rows)
      if (std::none_of(list_.rows.begin(), list_.rows.end(), [&](const auto& x) { return x[0] == line[0] && x[1] == line[1]; }))
        out.rows.push_back(line);
  if (!out.rows.empty()) write_csv(dir_ / kListName, out);
}

}  // namespace sdfbench
