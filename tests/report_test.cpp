// `table --keep-images` and `sdfbench report`: the kept images are the row's check frames, the
// page links every row to them, --render-missing reproduces a row's figures (and says so when
// it cannot), a CSV row reads back as the configuration that wrote it, and bad input is one error
// line. The page in a real browser: tests/report_browser_test.sh.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <regex>
#include <set>

#include "harness/benchmark_runner.h"
#include "harness/csv.h"
#include "harness/measurement.h"
#include "harness/row_configuration.h"
#include "harness/row_rerender.h"
#include "test_support.h"
#include "util/error.h"

namespace sdfbench {
namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), {}};
}

// Width, height and pixels (RGB floats) of a PNG, read by OpenImageIO.
struct Png {
  int width = 0, height = 0;
  std::vector<float> rgb;
};
Png read_png(const fs::path& path) {
  auto in = OIIO::ImageInput::open(path.string());
  EXPECT_TRUE(in) << path;
  if (!in) return {};
  const OIIO::ImageSpec& spec = in->spec();
  Png png{spec.width, spec.height, std::vector<float>(size_t(spec.width) * spec.height * 3)};
  in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, png.rgb.data());
  return png;
}

// A tiny table 6.3 with kept images: embree (the reference) and tri-aabb (the table's own
// backend), shadow mode, sphere:1 and sphere:10.
struct KeptTable {
  test::TempDir dir;
  fs::path csv = dir.path() / "out" / "t.csv";
  CsvTable rows;
  KeptTable() {
    fs::create_directories(csv.parent_path());
    const test::CommandResult r = test::run_sdfbench(
        "table --table 6.3 --meshes sphere --objects 1,10 --backends embree,tri-aabb --size 48x27 --check-size 48x27 "
        "--frames 1 --warmup 0 --csv " + csv.string() + " --keep-images " + (dir.path() / "out" / "kept").string());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    rows = read_csv(csv);
  }
  std::string field(size_t row, const char* column) const { return rows.rows.at(row)[rows.column(column)]; }
};

// `merge` of CSVs in another folder than the merged one: each image path is rebased onto the
// merged CSV's folder, so that it names the same file and the report takes it.
TEST(KeepImages, MergeRebasesImagePathsOntoTheMergedCsvsFolder) {
  KeptTable t;  // out/t.csv with out/kept/...
  const fs::path merged = t.dir.path() / "m.csv";
  const test::CommandResult m = test::run_sdfbench("merge " + t.csv.string() + " --csv " + merged.string());
  ASSERT_EQ(m.exit_code, 0) << m.output;
  const CsvTable rows = read_csv(merged);
  ASSERT_EQ(rows.rows.size(), 4u);
  for (size_t r = 0; r < rows.rows.size(); ++r) {
    const std::string path = rows.rows[r][rows.column("frame_image")];
    EXPECT_EQ(path, "out/" + t.field(r, "frame_image")) << "row " << r;
    EXPECT_TRUE(fs::exists(merged.parent_path() / path)) << path;
  }
  const test::CommandResult report =
      test::run_sdfbench("report " + merged.string() + " --out " + (t.dir.path() / "page.html").string());
  EXPECT_EQ(report.exit_code, 0) << report.output;
  EXPECT_NE(report.output.find("4 rows with kept images"), std::string::npos) << report.output;
}

// A snapshot commits its page's copies, not the run's kept images: a CSV whose kept images are
// not there reads as rows without images, and --render-missing renders and checks them again.
TEST(KeepImages, KeptImagesThatAreNotThereAreRenderedAgainOnRequest) {
  KeptTable t;
  fs::remove_all(t.dir.path() / "out" / "kept");
  const fs::path page = t.dir.path() / "page.html";
  const test::CommandResult plain = test::run_sdfbench("report " + t.csv.string() + " --out " + page.string());
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  EXPECT_NE(plain.output.find("0 rows with kept images, 0 re-rendered, 4 without images"), std::string::npos) << plain.output;
  EXPECT_NE(read_text(page).find("the kept images are not here"), std::string::npos);
  const test::CommandResult again = test::run_sdfbench("report " + t.csv.string() + " --render-missing --out " + page.string());
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_NE(again.output.find("4 re-rendered,"), std::string::npos) << again.output;
  EXPECT_EQ(again.output.find("whose figures differ"), std::string::npos) << again.output;
}

TEST(KeepImages, EveryRowNamesItsThreeCheckImagesBesideTheCsv) {
  KeptTable t;
  ASSERT_EQ(t.rows.rows.size(), 4u);
  std::set<std::string> frames;
  for (size_t r = 0; r < t.rows.rows.size(); ++r) {
    for (const char* column : {"frame_image", "reference_image", "diff_image"}) {
      const std::string path = t.field(r, column);
      ASSERT_EQ(path.rfind("kept/", 0), 0u) << column << " '" << path << "' is not relative to the CSV's folder";
      const Png png = read_png(t.csv.parent_path() / path);
      EXPECT_EQ(png.width, 48);
      EXPECT_EQ(png.height, 27);
    }
    frames.insert(t.field(r, "frame_image"));
  }
  EXPECT_EQ(frames.size(), 4u) << "each row keeps its own frame";
  // The reference row's frame is the reference, its difference map uniformly the map's zero colour;
  // tri-aabb's frame is its own render, not a copy of the reference's file.
  const Png ref = read_png(t.csv.parent_path() / t.field(0, "frame_image"));
  const Png ref_again = read_png(t.csv.parent_path() / t.field(1, "reference_image"));
  EXPECT_EQ(ref.rgb, ref_again.rgb);
  const Png diff = read_png(t.csv.parent_path() / t.field(0, "diff_image"));
  for (size_t i = 0; i < diff.rgb.size(); i += 3) ASSERT_EQ(diff.rgb[i], diff.rgb[0]) << "pixel " << i / 3;
  EXPECT_LT(diff.rgb[0] + diff.rgb[1] + diff.rgb[2], 1.2f) << "zero error is dark";
  // (tri-aabb draws what Embree draws to the last 8-bit step, so its frame says nothing about
  // whose render it is.) A backend whose frame differs, sdf-bricks with its own coarse field
  // hits: its kept frame is its render, not the reference's file, and its map shows the error.
  const fs::path csv = t.dir.path() / "field" / "f.csv";
  fs::create_directories(csv.parent_path());
  const test::CommandResult r = test::run_sdfbench(
      "table --table 6.3 --meshes sphere --objects 1 --backends embree,sdf-bricks --hit field --voxels 16 --size 48x27 "
      "--check-size 48x27 --frames 1 --warmup 0 --csv " + csv.string() + " --keep-images " + (csv.parent_path() / "kept").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const CsvTable field = read_csv(csv);
  const auto cell = [&](const char* column) { return csv.parent_path() / field.rows.at(1)[field.column(column)]; };
  EXPECT_NE(read_png(cell("frame_image")).rgb, read_png(cell("reference_image")).rgb);
  const Png map = read_png(cell("diff_image"));
  EXPECT_TRUE(std::any_of(map.rgb.begin(), map.rgb.end(), [&](float v) { return v != map.rgb[0]; })) << "a uniform difference map";
}

TEST(Report, LinksEveryRowToItsImagesAndCopiesThemBesideThePage) {
  KeptTable t;
  const fs::path page = t.dir.path() / "page" / "r.html";
  fs::create_directories(page.parent_path());
  const test::CommandResult r = test::run_sdfbench("report " + t.csv.string() + " --out " + page.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string html = read_text(page);
  EXPECT_NE(html.find("Table 6.3"), std::string::npos) << "the thesis' table with its values";
  EXPECT_NE(html.find("thesis "), std::string::npos);
  const std::regex row_re("<tr id=\"f0r(\\d+)\"");
  size_t rows = 0;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), row_re); it != std::sregex_iterator(); ++it) ++rows;
  EXPECT_EQ(rows, 4u);
  // Every image the page shows is in r_files/ and decodes; the row's frame is byte for byte the kept one.
  const std::regex img_re("<img src=\"(r_files/[0-9a-f]{16}\\.png)\"");
  size_t images = 0;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), img_re); it != std::sregex_iterator(); ++it, ++images)
    EXPECT_EQ(read_png(page.parent_path() / (*it)[1].str()).width, 48) << (*it)[1];
  EXPECT_EQ(images, 12u);
  const std::string kept_frame = read_text(t.csv.parent_path() / t.field(1, "frame_image"));
  bool found = false;
  for (const fs::directory_entry& e : fs::directory_iterator(page.parent_path() / "r_files")) found |= read_text(e.path()) == kept_frame;
  EXPECT_TRUE(found) << "tri-aabb's kept frame is on the page";
}

TEST(Report, RenderMissingReproducesTheRowsFiguresAndFlagsARowItCannot) {
  test::TempDir dir;
  const fs::path csv = dir.path() / "t.csv";
  const test::CommandResult run = test::run_sdfbench(
      "table --table 6.3 --mode shadow --meshes sphere --objects 10 --backends embree,bvh,sdf-octree --size 48x27 "
      "--check-size 64x36 --frames 1 --warmup 0 --csv " + csv.string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  // The same rows again, one with a PSNR that the frame does not have.
  CsvTable tampered = read_csv(csv);
  tampered.rows[2][tampered.column("psnr")] = "12.5";
  write_csv(dir.path() / "tampered.csv", tampered);
  const fs::path page = dir.path() / "r.html";
  const test::CommandResult r = test::run_sdfbench("report " + csv.string() + " " + (dir.path() / "tampered.csv").string() +
                                                   " --render-missing --out " + page.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("6 re-rendered (1 whose figures differ from the row's)"), std::string::npos) << r.output;
  const std::string html = read_text(page);
  size_t equal = 0;
  for (size_t at = html.find("agreement figures equal the row"); at != std::string::npos; at = html.find("agreement figures equal the row", at + 1)) ++equal;
  EXPECT_EQ(equal, 3u) << "bvh twice and sdf-octree once reproduce their rows (the reference rows are the reference)";
  EXPECT_NE(html.find("psnr 12.5 → "), std::string::npos);
  EXPECT_NE(html.find("<tr id=\"f1r2\" class=\"bad\""), std::string::npos) << "the tampered row is flagged";
  // Written again, nothing is rendered again: the list of rendered rows is reused.
  const test::CommandResult again = test::run_sdfbench("report " + csv.string() + " --render-missing --out " + page.string());
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_EQ(again.output.find("rendering the check frame"), std::string::npos) << again.output;
  // The list is keyed by the CSV's real path: the same file spelled another way is the same file.
  const test::CommandResult spelled = test::run_sdfbench("report " + (dir.path() / "." / "t.csv").string() +
                                                         " --render-missing --out " + page.string());
  ASSERT_EQ(spelled.exit_code, 0) << spelled.output;
  EXPECT_EQ(spelled.output.find("rendering the check frame"), std::string::npos) << spelled.output;
}

TEST(Report, BadInputIsOneErrorLine) {
  KeptTable t;
  const fs::path out = t.dir.path() / "r.html";
  auto expect_error = [](const test::CommandResult& r, const std::string& says) {
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_EQ(r.output.rfind("sdfbench: error: ", 0), 0u) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << "one line: " << r.output;
    EXPECT_NE(r.output.find(says), std::string::npos) << r.output;
  };
  expect_error(test::run_sdfbench("report " + t.csv.string() + " --out " + (t.dir.path() / "r.txt").string()), "name it *.html");
  expect_error(test::run_sdfbench("report " + t.csv.string() + " --out " + out.string() + " --plots " + t.csv.string()),
               "is not a folder");
  // A kept image that is gone, or not a PNG: the file, row and column are named.
  CsvTable rows = t.rows;
  rows.rows[1][rows.column("diff_image")] = "kept/missing.png";
  write_csv(t.csv.parent_path() / "gone.csv", rows);
  expect_error(test::run_sdfbench("report " + (t.csv.parent_path() / "gone.csv").string() + " --out " + out.string()),
               "gone.csv' row 2: diff_image");
  rows.rows[1][rows.column("diff_image")] = "t.csv";
  write_csv(t.csv.parent_path() / "notpng.csv", rows);
  expect_error(test::run_sdfbench("report " + (t.csv.parent_path() / "notpng.csv").string() + " --out " + out.string()),
               "is not a PNG image");
  expect_error(test::run_sdfbench("table --keep-images " + t.csv.string() + " --meshes sphere --objects 1 --backends embree"),
               "--keep-images");
  EXPECT_FALSE(fs::exists(out)) << "no page after an error";
}

// Every configuration a table or sweep writes reads back from its CSV row as itself.
TEST(RowConfiguration, ARowReadsBackAsTheConfigurationThatWroteIt) {
  std::vector<BenchConfig> configs(4);
  configs[0].scene = "thesis:bunny:10";
  configs[0].backend = "embree";
  configs[0].size = {64, 36};
  configs[1] = configs[0];
  configs[1].backend = "sdf-octree";
  configs[1].mode = RenderMode::Whitted;
  configs[1].max_depth = 3;
  configs[1].options.params.set("hash_cell", "5");
  configs[1].options.params.set("octree_depth", "2");
  configs[1].options.params.set("lists", "thesis");
  configs[1].options.params.set("cells_per_extent", "48");
  configs[1].options.params.set("fixed_grid", "1");
  configs[1].options.params.set("hit", "thesis");
  configs[1].options.params.set("over_relax", "1.5");
  configs[1].options.params.set("cell_bound", "1");
  configs[1].options.params.set("storage_tables", "1");
  configs[1].options.whitted_passes = true;
  configs[2] = configs[0];
  configs[2].backend = "sdf-global";
  configs[2].mode = RenderMode::Shadow;
  configs[2].options.params.set("global_voxel", "0.5");
  configs[2].options.params.set("sdf_format", "f16");
  configs[2].options.params.set("hit", "field");
  configs[3] = configs[0];
  configs[3].backend = "sdf-hash";  // hash cell 1 unless given
  BenchSettings settings;
  settings.check_size = {80, 45};
  settings.reference = "embree";
  CsvTable table;
  table.columns = measurement_columns();
  table.source = "configs.csv";
  for (size_t i = 0; i < configs.size(); ++i) table.rows.push_back(to_csv_fields(configuration_fields(configs[i], i, settings)));
  for (size_t i = 0; i < configs.size(); ++i) {
    const RowConfiguration read = row_configuration(table, i);
    EXPECT_EQ(configuration_key(configuration_fields(read.config, i, settings)), configuration_key(table.rows[i], table.columns))
        << configs[i].backend;
    // Against the configuration itself, not only through the one encoder (which a column it
    // dropped on both sides would pass): every value that was set reads back as it was.
    EXPECT_EQ(read.config.scene, configs[i].scene);
    EXPECT_EQ(read.config.backend, configs[i].backend);
    EXPECT_EQ(read.config.mode, configs[i].mode);
    EXPECT_EQ(read.config.size.width, configs[i].size.width);
    EXPECT_EQ(read.config.size.height, configs[i].size.height);
    EXPECT_EQ(read.config.max_depth, configs[i].max_depth) << configs[i].backend;
    EXPECT_EQ(read.config.options.whitted_passes, configs[i].options.whitted_passes) << configs[i].backend;
    for (const auto& [name, value] : configs[i].options.params.values()) {
      ASSERT_TRUE(read.config.options.params.has(name)) << configs[i].backend << ": " << name << " was not read back";
      EXPECT_EQ(read.config.options.params.text(name), value) << configs[i].backend << ": " << name;
    }
    EXPECT_EQ(read.check_size.width, 80u);
    EXPECT_EQ(read.reference, "embree");
  }
  table.rows[1][table.column("octree_depth")] = "two";
  try {
    row_configuration(table, 1);
    ADD_FAILURE() << "a bad field was read";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'configs.csv' row 2, column octree_depth"), std::string::npos) << e.what();
  }
}

// Issue 36: the committed results read back as configurations under the registry's declarations
// (what `report --render-missing` renders them from), every row of every CSV.
TEST(RowConfiguration, EveryCommittedCsvReadsBack) {
  const fs::path results = fs::path(SDFBENCH_DATA_DIR).parent_path() / "results";
  size_t files = 0, rows = 0;
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(results)) {
    if (entry.path().extension() != ".csv") continue;
    const CsvTable table = read_csv(entry.path());
    if (!table.has_column("run_index") || !table.has_column("backend")) continue;  // not a results CSV
    ++files;
    for (size_t r = 0; r < table.rows.size(); ++r, ++rows) EXPECT_NO_THROW(row_configuration(table, r)) << entry.path() << " row " << r + 1;
  }
  EXPECT_GE(files, 10u);
  EXPECT_GE(rows, 600u);
}

// Issue 36: a key column is read back with the declaration of its flag, so a value the flag would
// refuse (or that would overflow the type it is used as) is an error naming file, row and column,
// also through `report --render-missing`.
TEST(RowConfiguration, AValueItsFlagWouldRefuseIsAnErrorNamingFileRowAndColumn) {
  BenchConfig config;
  config.scene = "thesis:sphere:1";
  config.backend = "sdf-octree";
  config.size = {32, 18};
  BenchSettings settings;
  settings.check_size = {32, 18};
  settings.reference = "embree";
  CsvTable table;
  table.columns = measurement_columns();
  table.source = "bad.csv";
  table.rows.push_back(to_csv_fields(configuration_fields(config, 0, settings)));
  ASSERT_NO_THROW(row_configuration(table, 0));
  const std::pair<const char*, const char*> bad[] = {{"max_steps", "0"},       {"hit_epsilon", "0.5"}, {"max_steps", "1e20"},
                                                      {"octree_depth", "1e20"}, {"hash_cell", "-1"},   {"lists", "both"},
                                                      {"max_depth", "1e20"},    {"threads", "4294967296"}};
  for (const auto& [column, value] : bad) {
    CsvTable t = table;
    t.rows[0][t.column(column)] = value;
    try {
      row_configuration(t, 0);
      ADD_FAILURE() << column << " " << value << " was read";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("'bad.csv' row 1, column " + std::string(column)), std::string::npos) << e.what();
    }
  }
  test::TempDir dir;
  CsvTable t = table;
  t.rows[0][t.column("hit_epsilon")] = "0.5";
  write_csv(dir.path() / "bad.csv", t);
  const test::CommandResult r =
      test::run_sdfbench("report " + (dir.path() / "bad.csv").string() + " --render-missing --out " + (dir.path() / "r.html").string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("row 1, column hit_epsilon: expected a number in [1e-08, 0.01], got '0.5'"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace sdfbench

namespace sdfbench {
namespace {

// A re-render reproduces a row when its figures differ by float rounding only, and not when a
// pixel or a PSNR that means something differs.
TEST(Report, ARerenderReproducesARowWithinRoundingOnly) {
  CsvTable t;
  t.columns = {"scene", "backend", "mode", "width", "height", "check_size", "hit_agreement", "id_agreement", "psnr", "depth_p99"};
  t.rows = {{"thesis:bunny:1", "bvh", "primary", "64", "36", "320x180", "99.9", "100", "137.31", "1.3e-07"}};
  t.source = "t.csv";
  Rerender r;
  r.hit_agreement = "99.9";
  r.id_agreement = "100";
  r.psnr = "137.309";  // both above 100 dB: float rounding, no 8-bit pixel differs
  r.depth_p99 = "1.30001e-07";
  EXPECT_EQ(rerender_differences(t, 0, r), "");
  r.hit_agreement = "99.8983";  // one pixel of 320x180 is 0.0017 %
  EXPECT_EQ(rerender_differences(t, 0, r), "hit_agreement 99.9 → 99.8983");
  r.hit_agreement = "99.9";
  t.rows[0][t.column("psnr")] = "45.2";
  r.psnr = "45.25";
  EXPECT_EQ(rerender_differences(t, 0, r), "psnr 45.2 → 45.25");
  r.psnr = "45.2";
  r.depth_p99 = "2e-07";
  EXPECT_EQ(rerender_differences(t, 0, r), "depth_p99 1.3e-07 → 2e-07");
  r.reference_row = true;  // the reference's own row has no figures to reproduce
  EXPECT_EQ(rerender_differences(t, 0, r), "");
}

}  // namespace
}  // namespace sdfbench

namespace sdfbench {
namespace {

// The report's folder is shared (issue 39): every string from a CSV or a file name is escaped,
// only images inside the CSV's folder at the row's check size are copied, only images a report
// wrote are removed, and a failed report leaves no folder behind.
TEST(Report, TheSharedFolderHoldsOnlyWhatTheRowsName) {
  KeptTable t;
  const fs::path folder = t.csv.parent_path();
  const fs::path page = t.dir.path() / "page" / "r.html";
  fs::create_directories(page.parent_path());
  auto report = [&](const CsvTable& rows, const std::string& extra = "") {
    write_csv(folder / "edited.csv", rows);
    return test::run_sdfbench("report " + (folder / "edited.csv").string() + " --out " + page.string() + extra);
  };
  auto expect_error = [](const test::CommandResult& r, const std::string& says) {
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_EQ(r.output.rfind("sdfbench: error: ", 0), 0u) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_NE(r.output.find(says), std::string::npos) << r.output;
  };
  // Markup in every text column and in a plot's file name stays text.
  CsvTable hostile = t.rows;
  for (const char* column : {"width", "height", "scene", "backend", "mode", "device", "commit", "agreement", "run_index"})
    for (auto& row : hostile.rows) row[hostile.column(column)] = "<script>alert(1)</script>\"'";
  fs::create_directories(t.dir.path() / "plots");
  fs::copy_file(folder / t.field(0, "frame_image"), t.dir.path() / "plots" / "<script>x.png");
  const test::CommandResult shown = report(hostile, " --plots " + (t.dir.path() / "plots").string());
  ASSERT_EQ(shown.exit_code, 0) << shown.output;
  const std::string html = read_text(page);
  EXPECT_EQ(html.find("<script"), std::string::npos) << "unescaped markup from the CSV or a file name";
  EXPECT_NE(html.find("&lt;script&gt;"), std::string::npos);

  // Image columns: outside the CSV's folder (absolute, .., a symlink out of it), or another size.
  CsvTable rows = t.rows;
  const std::string kept = t.field(1, "frame_image");
  for (const std::string& outside : {(folder / kept).string(), std::string("../plots/<script>x.png"), std::string("link.png")}) {
    fs::remove(folder / "link.png");
    fs::create_symlink(t.dir.path() / "plots" / "<script>x.png", folder / "link.png");
    rows.rows[1][rows.column("frame_image")] = outside;
    expect_error(report(rows), "row 2: frame_image: '" + outside + "' is not a file inside the CSV's folder");
  }
  const unsigned char header[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13, 'I', 'H', 'D', 'R',
                                  0, 1, 0x86, 0xa0, 0, 1, 0x86, 0xa0, 8, 2, 0, 0, 0, 0, 0, 0, 0};  // 100000 x 100000
  std::ofstream(folder / "kept" / "huge.png", std::ios::binary).write(reinterpret_cast<const char*>(header), sizeof header);
  rows.rows[1][rows.column("frame_image")] = "kept/huge.png";
  expect_error(report(rows), "declares 100000x100000 pixels, not the row's check size 48x27");

  // Removal: a report removes the images it wrote that the new page does not link, and nothing
  // else. (The failed runs above left the folder from the first report as it was.)
  ASSERT_EQ(report(t.rows).exit_code, 0);
  const fs::path files = page.parent_path() / "r_files";
  std::ofstream(files / "mine.png") << "a user's file";
  const size_t before = std::distance(fs::directory_iterator(files), fs::directory_iterator());
  CsvTable one = t.rows;
  one.rows.resize(1);
  ASSERT_EQ(report(one).exit_code, 0);
  EXPECT_TRUE(fs::exists(files / "mine.png"));
  EXPECT_LT(std::distance(fs::directory_iterator(files), fs::directory_iterator()), before);

  // Folders: a symlinked or foreign image folder, --keep-images into a report's folder or onto
  // the CSV; a failed report leaves no folder it made.
  const fs::path other = t.dir.path() / "other" / "s.html";
  fs::create_directories(other.parent_path() / "s_files");
  std::ofstream(other.parent_path() / "s_files" / "holiday.png") << "x";
  expect_error(test::run_sdfbench("report " + t.csv.string() + " --out " + other.string()), "holds files that no sdfbench report wrote");
  fs::remove_all(other.parent_path() / "s_files");
  fs::create_directory_symlink(files, other.parent_path() / "s_files");
  expect_error(test::run_sdfbench("report " + t.csv.string() + " --out " + other.string()), "is a symbolic link");
  const std::string table = "table --meshes sphere --objects 1 --backends embree --size 8x8 --frames 1 --warmup 0 --csv " +
                            (t.dir.path() / "k.csv").string();
  expect_error(test::run_sdfbench(table + " --keep-images " + files.string()), "is a report's image folder");
  expect_error(test::run_sdfbench(table + " --keep-images " + (t.dir.path() / "k.csv").string()), "--keep-images");
  EXPECT_FALSE(fs::exists(t.dir.path() / "k.csv"));
  rows.rows[1][rows.column("frame_image")] = "kept/huge.png";
  write_csv(folder / "edited.csv", rows);
  const fs::path fresh = t.dir.path() / "fresh" / "f.html";
  fs::create_directories(fresh.parent_path());
  expect_error(test::run_sdfbench("report " + (folder / "edited.csv").string() + " --out " + fresh.string()), "huge.png");
  EXPECT_FALSE(fs::exists(fresh.parent_path() / "f_files")) << "a failed report left its image folder";
  expect_error(test::run_sdfbench("report " + t.csv.string() + " --out " + fresh.string() + " --plots /proc"),
               "--plots '/proc': cannot read");
}

}  // namespace
}  // namespace sdfbench
