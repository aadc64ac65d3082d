// `sdfbench report`: one HTML page (harness/html_report.h) from measurement CSVs, the check
// images their runs kept (--keep-images) and plots; images go to a folder beside the page.
#include <algorithm>
#include <filesystem>
#include <iostream>

#include "harness/commands.h"
#include "harness/html_report.h"
#include "harness/output_paths.h"
#include "harness/image_store.h"
#include "harness/kept_images.h"
#include "harness/row_rerender.h"
#include "harness/row_verdict.h"
#include "harness/run_options.h"
#include "harness/system_info.h"
#include "util/atomic_file.h"
#include "util/error.h"

namespace sdfbench {
namespace {

namespace fs = std::filesystem;

struct ReportArgs {
  std::vector<std::string> inputs, plots;
  std::string out, device;
  bool render_missing = false;
};

// The page's note for a re-rendered row, and whether it is not the row's (≠).
RowImages rerendered_images(const CsvTable& t, size_t row, const Rerender& r) {
  const std::string differences = rerender_differences(t, row, r);
  const std::string measured_at = t.has_column("commit") ? t.rows[row][t.column("commit")] : std::string("?");
  return {r.frame, r.reference, r.diff,
          "re-rendered by sdfbench " + r.sdfbench + " from the row's configuration (measured at " + measured_at + "): " +
              (r.reference_row ? "the reference itself"
               : differences.empty() ? "agreement figures equal the row's"
                                     : "agreement figures differ (" + differences + "): not the row's images"),
          !differences.empty()};
}

std::vector<ReportPlot> collect_plots(const std::vector<std::string>& dirs, ImageStore& store) {
  std::vector<ReportPlot> plots;
  for (const std::string& dir : dirs) {
    if (!fs::is_directory(dir)) throw Error("--plots '" + dir + "' is not a folder");
    std::vector<fs::path> files;
    std::error_code ec;
    for (auto it = fs::recursive_directory_iterator(dir, fs::directory_options::none, ec); !ec && it != fs::recursive_directory_iterator();
         it.increment(ec))
      if (it->is_regular_file(ec) && it->path().extension() == ".png") files.push_back(it->path());
    if (ec) throw Error("--plots '" + dir + "': cannot read the folder: " + ec.message());
    std::sort(files.begin(), files.end());
    for (const fs::path& p : files)
      plots.push_back({store.add_file(p, "--plots image"), p.lexically_relative(dir).string()});
  }
  return plots;
}

// The page's image folder: made by this report, or one an earlier report made (its marker);
// never a symlink or a folder of other files.
bool prepare_report_folder(const fs::path& dir) {
  std::error_code ec;
  if (fs::is_symlink(dir, ec)) throw Error("--out's image folder '" + dir.string() + "' is a symbolic link; name another --out");
  const bool created = !fs::exists(dir, ec);
  if (!created && fs::is_directory(dir, ec) && !fs::exists(dir / ImageStore::kOwnerMarker, ec) && !fs::is_empty(dir, ec))
    throw Error("--out's image folder '" + dir.string() + "' holds files that no sdfbench report wrote (no " +
                ImageStore::kOwnerMarker + "); name another --out or move them");
  prepare_image_folder(dir, "--out's image folder");
  if (!fs::exists(dir / ImageStore::kOwnerMarker, ec)) write_file_atomically(dir / ImageStore::kOwnerMarker, {});
  return created;
}

void write_report(const ReportArgs& args, std::vector<ReportFile>& files, const fs::path& out, const fs::path& files_dir);

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
  const OutputLock lock(out, "--out");  // not while another report writes this page
  const bool created = prepare_report_folder(files_dir);
  try {
    write_report(args, files, out, files_dir);
  } catch (...) {
    std::error_code ec;
    if (created) fs::remove_all(files_dir, ec);  // no half-made folder: it held nothing before
    throw;
  }
}

void write_report(const ReportArgs& args, std::vector<ReportFile>& files, const fs::path& out, const fs::path& files_dir) {
  ImageStore store(files_dir, files_dir.filename().string() + "/");
  RowRerenderer rerenderer(store, files_dir, args.device);

  size_t kept = 0, rendered = 0, mismatched = 0, without = 0;
  for (ReportFile& file : files) {
    const CsvTable& t = file.table;
    for (size_t row = 0; row < t.rows.size(); ++row) {
      RowImages images;
      const std::string where = "'" + t.source + "' row " + std::to_string(row + 1);
      auto field = [&](const char* column) { return t.has_column(column) ? t.rows[row][t.column(column)] : std::string(); };
      const bool failed = row_verdict(t, t.rows[row]).is_error();
      // Images the row names but that are not there (a snapshot commits its page's copies, not
      // the run's kept images) are missing images: rendered again with --render-missing.
      const bool kept_here = !field("frame_image").empty() && kept_images_present(t, row);
      if (kept_here) {
        images = kept_images(t, row, store);
        images.note = "kept by the run";
        ++kept;
      } else if (failed) {
        images.note = "the configuration failed: no images";
      } else if (args.render_missing) {
        if (!rerenderer.listed(t, row))
          std::cerr << "[" << (rendered + 1) << "] " << where << ": rendering the check frame of " << field("backend") << " "
                    << field("mode") << " " << field("scene") << "\n";
        try {
          images = rerendered_images(t, row, rerenderer.get(t, row));
        } catch (const Error& e) {
          throw Error(where + ": " + e.what());
        }
        ++rendered;
        mismatched += images.mismatch;
      } else {
        images.note = field("frame_image").empty() ? "no images kept (table/sweep --keep-images, or report --render-missing)"
                                                   : "the kept images are not here (report --render-missing renders them)";
        ++without;
      }
      file.images.push_back(std::move(images));
    }
  }
  const std::vector<ReportPlot> plots = collect_plots(args.plots, store);
  const std::string html = html_report(files, plots, ThesisTables::load_default(), git_commit());
  write_file_atomically(out, std::as_bytes(std::span(html.data(), html.size())));
  if (args.render_missing) rerenderer.write_list(false);
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
