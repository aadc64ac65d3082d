// `sdfbench report`: one HTML page (harness/html_report.h) from measurement CSVs, the check
// images their runs kept (--keep-images) and plots; images go to a folder beside the page.
#include <algorithm>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>
#include <set>

#include "harness/commands.h"
#include "harness/html_report.h"
#include "harness/image_output.h"
#include "harness/measurement.h"
#include "harness/output_paths.h"
#include "harness/row_configuration.h"
#include "harness/run_options.h"
#include "harness/system_info.h"
#include "util/atomic_file.h"
#include "util/error.h"
#include "util/fnv1a.h"
#include "util/input_file.h"

namespace sdfbench {
namespace {

namespace fs = std::filesystem;

struct ReportArgs {
  std::vector<std::string> inputs, plots;
  std::string out, device;
  bool render_missing = false;
};

constexpr uint64_t kMaxImageBytes = uint64_t{64} << 20;
// In a folder with this file the report owns every PNG: those no page links to any more go.
constexpr const char* kOwnerMarker = ".sdfbench-report";

// The page's image folder: every image stored once under the digest of its bytes, so a
// reference shared by many rows (and a frame equal to it) costs its bytes once.
class ImageStore {
 public:
  ImageStore(fs::path dir, std::string href_prefix) : dir_(std::move(dir)), prefix_(std::move(href_prefix)) {}

  std::string add(std::span<const std::byte> png) {
    char name[32];
    std::snprintf(name, sizeof name, "%016llx.png", static_cast<unsigned long long>(fnv1a64(png)));
    if (names_.insert(name).second && !fs::exists(dir_ / name)) write_file_atomically(dir_ / name, png);
    return prefix_ + name;
  }
  std::string add(const FloatImage& image) {
    const std::vector<unsigned char> png = encode_image(image, ImageFormat::png, "report image");
    return add(std::as_bytes(std::span(png.data(), png.size())));
  }
  std::string add_file(const fs::path& path, const std::string& what) {
    const std::vector<std::byte> bytes = read_input_bytes(path, what, kMaxImageBytes);
    static const unsigned char magic[] = {0x89, 'P', 'N', 'G'};
    if (bytes.size() < 4 || std::memcmp(bytes.data(), magic, 4) != 0)
      throw Error(what + " '" + path.string() + "' is not a PNG image");
    return add(bytes);
  }
  // With the owner marker in the folder: removes the PNGs this page does not link.
  void remove_unlinked() const {
    if (!fs::exists(dir_ / kOwnerMarker)) return;
    for (const fs::directory_entry& e : fs::directory_iterator(dir_))
      if (e.is_regular_file() && e.path().extension() == ".png" && !names_.count(e.path().filename().string())) fs::remove(e.path());
  }

 private:
  fs::path dir_;
  std::string prefix_;
  std::set<std::string> names_;
};

// The row's agreement figures as the CSV writes them, against those of a re-rendered frame:
// empty when equal, else what differs.
std::string figure_differences(const CsvTable& t, size_t row, const Agreement& g) {
  std::string differences;
  auto compare = [&](const char* column, std::optional<double> value) {
    const std::string ours = value ? csv_number(*value) : "";
    if (!t.has_column(column)) return;  // an older CSV: the figure was not recorded
    const std::string& theirs = t.rows[row][t.column(column)];
    if (ours != theirs) differences += std::string(differences.empty() ? "" : ", ") + column + " " + theirs + " → " + ours;
  };
  compare("hit_agreement", g.hit_percent);
  compare("id_agreement", g.id_percent);
  compare("psnr", g.psnr);
  compare("depth_p99", g.depth_p99);
  compare("depth_p99_voxels", g.depth_p99_voxels);
  return differences;
}

// Renders the check frames of rows that kept none, one runner per reference and check size.
// What it rendered is listed in the image folder's kRenderedList, so writing the page again (a
// CSV added, a plot changed) renders only rows it has not rendered before.
class MissingImages {
 public:
  static constexpr const char* kRenderedList = "rendered.csv";

  MissingImages(ImageStore& store, fs::path dir, std::string device) : store_(store), dir_(std::move(dir)), device_(std::move(device)) {
    list_.columns = {"csv", "key", "frame", "reference", "diff", "note", "mismatch"};
    if (fs::exists(dir_ / kRenderedList)) {
      const CsvTable old = read_csv(dir_ / kRenderedList);
      if (old.columns == list_.columns) previous_ = old;
    }
  }

  // A row rendered before (same file, same configuration, its images still there), or nothing.
  std::optional<RowImages> rendered_before(const CsvTable& t, size_t row) {
    const std::string key = configuration_key(t.rows[row], t.columns);
    for (const auto& r : previous_.rows) {
      if (r[0] != t.source || r[1] != key) continue;
      const std::string prefix = dir_.filename().string() + "/";
      for (int i = 2; i <= 4; ++i)
        if (r[i].rfind(prefix, 0) != 0 || !fs::exists(dir_ / r[i].substr(prefix.size()))) return std::nullopt;
      RowImages images{store_.add_file(dir_ / r[2].substr(prefix.size()), "rendered image"),
                       store_.add_file(dir_ / r[3].substr(prefix.size()), "rendered image"),
                       store_.add_file(dir_ / r[4].substr(prefix.size()), "rendered image"), r[5], r[6] == "1"};
      remember(t, row, images);
      return images;
    }
    return std::nullopt;
  }

  RowImages render(const CsvTable& t, size_t row) {
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
    RowImages images{store_.add(color_image(checked.frame)), store_.add(color_image(checked.reference)),
                     store_.add(difference_map(checked.frame, checked.reference)), "", false};
    const bool is_reference = rc.config.backend == rc.reference;
    const std::string differences = is_reference ? "" : figure_differences(t, row, checked.agreement);
    images.mismatch = !differences.empty();
    images.note = "re-rendered by sdfbench " + git_commit() + " from the row's configuration (commit " +
                  (t.has_column("commit") ? t.rows[row][t.column("commit")] : std::string("?")) + "): " +
                  (is_reference ? "the reference itself"
                   : differences.empty() ? "agreement figures equal the row's"
                                         : "agreement figures differ (" + differences + "), not the row's images");
    remember(t, row, images);
    // After every row, with the earlier list's rows not (yet) reached: an interrupted report keeps both.
    CsvTable progress = list_;
    for (const auto& r : previous_.rows)
      if (std::none_of(list_.rows.begin(), list_.rows.end(), [&](const auto& x) { return x[0] == r[0] && x[1] == r[1]; }))
        progress.rows.push_back(r);
    write_csv(dir_ / kRenderedList, progress);
    return images;
  }

  void write_list() const {
    if (!list_.rows.empty()) write_csv(dir_ / kRenderedList, list_);
  }

 private:
  void remember(const CsvTable& t, size_t row, const RowImages& images) {
    list_.rows.push_back({t.source, configuration_key(t.rows[row], t.columns), images.frame, images.reference, images.diff,
                          images.note, images.mismatch ? "1" : "0"});
  }

  ImageStore& store_;
  fs::path dir_;
  CsvTable list_, previous_;
  std::string device_;
  std::map<std::string, std::unique_ptr<BenchmarkRunner>> runners_;
};

std::vector<ReportPlot> collect_plots(const std::vector<std::string>& dirs, ImageStore& store) {
  std::vector<ReportPlot> plots;
  for (const std::string& dir : dirs) {
    if (!fs::is_directory(dir)) throw Error("--plots '" + dir + "' is not a folder");
    std::vector<fs::path> files;
    for (const fs::directory_entry& e : fs::recursive_directory_iterator(dir))
      if (e.is_regular_file() && e.path().extension() == ".png") files.push_back(e.path());
    std::sort(files.begin(), files.end());
    for (const fs::path& p : files)
      plots.push_back({store.add_file(p, "--plots image"), p.lexically_relative(dir).string()});
  }
  return plots;
}

void run_report(const ReportArgs& args) {
  const fs::path out = args.out;
  if (out.extension() != ".html") throw Error("--out '" + args.out + "': the report is an HTML page; name it *.html");
  check_output_path(out, "--out");
  const fs::path files_dir = out.parent_path() / (out.stem().string() + "_files");
  std::vector<NamedPath> inputs;
  for (const std::string& path : args.inputs) inputs.push_back({"the input CSV", path});
  check_distinct_outputs({{"--out", out}}, inputs);
  std::vector<ReportFile> files;
  for (const std::string& path : args.inputs) files.push_back({read_csv(path), {}});
  const bool created = !fs::exists(files_dir);
  prepare_image_folder(files_dir, "--out's image folder");
  if (created) write_file_atomically(files_dir / kOwnerMarker, {});
  ImageStore store(files_dir, files_dir.filename().string() + "/");
  MissingImages missing(store, files_dir, args.device);

  size_t kept = 0, rendered = 0, mismatched = 0, without = 0;
  for (ReportFile& file : files) {
    const CsvTable& t = file.table;
    const fs::path base = fs::path(t.source).parent_path();
    for (size_t row = 0; row < t.rows.size(); ++row) {
      RowImages images;
      const std::string where = "'" + t.source + "' row " + std::to_string(row + 1);
      auto field = [&](const char* column) { return t.has_column(column) ? t.rows[row][t.column(column)] : std::string(); };
      const bool failed = field("agreement").rfind("ERROR", 0) == 0;
      if (!field("frame_image").empty()) {
        images.frame = store.add_file(base / field("frame_image"), where + ": frame_image");
        images.reference = store.add_file(base / field("reference_image"), where + ": reference_image");
        images.diff = store.add_file(base / field("diff_image"), where + ": diff_image");
        images.note = "kept by the run";
        ++kept;
      } else if (failed) {
        images.note = "the configuration failed: no images";
      } else if (std::optional<RowImages> before = args.render_missing ? missing.rendered_before(t, row) : std::nullopt) {
        images = std::move(*before);
        ++rendered;
        mismatched += images.mismatch;
      } else if (args.render_missing) {
        std::cerr << "[" << (rendered + 1) << "] " << where << ": rendering the check frame of " << field("backend") << " "
                  << field("mode") << " " << field("scene") << "\n";
        try {
          images = missing.render(t, row);
        } catch (const Error& e) {
          throw Error(where + ": " + e.what());
        }
        ++rendered;
        mismatched += images.mismatch;
      } else {
        images.note = "no images kept (table/sweep --keep-images, or report --render-missing)";
        ++without;
      }
      file.images.push_back(std::move(images));
    }
  }
  const std::vector<ReportPlot> plots = collect_plots(args.plots, store);
  const std::string html = html_report(files, plots, ThesisTables::load_default(), git_commit());
  write_file_atomically(out, std::as_bytes(std::span(html.data(), html.size())));
  missing.write_list();
  store.remove_unlinked();
  std::cout << "report: " << out.string() << " (images in " << files_dir.string() << "/): " << kept << " rows with kept images, "
            << rendered << " re-rendered" << (mismatched ? " (" + std::to_string(mismatched) + " whose figures differ from the row's)" : "")
            << ", " << without << " without images, " << plots.size() << " plots\n";
}

}  // namespace

void register_report_command(CLI::App& app) {
  auto args = std::make_shared<ReportArgs>();
  CLI::App* cmd = app.add_subcommand(
      "report", "Write one HTML page from measurement CSVs: environment, the thesis' tables with ratios, plots, and every "
                "row with its check images (kept by table/sweep --keep-images)");
  cmd->add_option("inputs", args->inputs, "CSV files written by table, sweep or merge")->required();
  cmd->add_option("--out", args->out, "the page (*.html); its images go to <name>_files/ beside it")->required();
  cmd->add_option("--plots", args->plots, "a folder of PNG plots (plot_results.py --out-dir) shown on the page; repeatable");
  cmd->add_flag("--render-missing", args->render_missing,
                "rows that kept no images: render their check frames again from the row's configuration and say "
                "whether the agreement figures equal the row's (≠ when not)");
  cmd->add_option("--device", args->device, "with --render-missing: the Vulkan device to render on (default: each row's)");
  cmd->callback([args] { run_report(*args); });
}

}  // namespace sdfbench
