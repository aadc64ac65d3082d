// Fuzz target for what `report` takes from a CSV (harness/csv.h, harness/kept_images.h, the
// image store): hostile CSVs whose image columns name files inside and outside the CSV's folder.
// Every input is read, or refused with sdfbench::Error; and whatever it names, the report's
// folder receives only copies of the PNGs inside the CSV's folder (kept/frame.png, 4x3, and
// big.png, 8x6, each at its rows' check size): never the PNG beside the folder, the one a
// symlink leads to, or anything else. Built and run like the other text targets (tests/CMakeLists.txt).
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <string>
#include <unistd.h>

#include "harness/csv.h"
#include "harness/image_store.h"
#include "harness/kept_images.h"
#include "util/atomic_file.h"
#include "util/error.h"
#include "util/fnv1a.h"
#include "util/image_codec.h"

namespace {

namespace fs = std::filesystem;

std::vector<unsigned char> png(uint32_t width, uint32_t height, float value) {
  sdfbench::FloatImage image{width, height, {"R", "G", "B"}, std::vector<float>(size_t(width) * height * 3, value)};
  return sdfbench::encode_image(image, sdfbench::ImageFormat::png, "fuzz image");
}

void write(const fs::path& path, const std::vector<unsigned char>& bytes) {
  sdfbench::write_file_atomically(path, std::as_bytes(std::span(bytes.data(), bytes.size())));
}

// The world the CSVs point into: root/csvs/ (the CSV's folder) with kept/frame.png and a
// symlink kept/link.png to root/outside.png; root/report_files/ is the report's folder.
struct World {
  fs::path root, csvs, files;
  std::set<std::string> allowed;  // the names a copy may have
  World() {
    char tmpl[] = "/tmp/sdfbench_report_fuzz_XXXXXX";
    root = mkdtemp(tmpl);
    csvs = root / "csvs";
    files = root / "report_files";
    fs::create_directories(csvs / "kept");
    fs::create_directories(files);
    const std::vector<unsigned char> inside = png(4, 3, 0.5f), big = png(8, 6, 0.5f);
    write(csvs / "kept" / "frame.png", inside);
    write(csvs / "big.png", big);
    write(root / "outside.png", png(4, 3, 0.9f));
    fs::create_symlink(root / "outside.png", csvs / "kept" / "link.png");
    for (const auto* bytes : {&inside, &big}) {
      char name[32];
      std::snprintf(name, sizeof name, "%016llx.png",
                    static_cast<unsigned long long>(sdfbench::fnv1a64(std::as_bytes(std::span(bytes->data(), bytes->size())))));
      allowed.insert(name);
    }
  }
  ~World() {
    std::error_code ec;
    fs::remove_all(root, ec);
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const World world;
  try {
    const sdfbench::CsvTable table =
        sdfbench::parse_csv(std::string(reinterpret_cast<const char*>(data), size), (world.csvs / "t.csv").string());
    sdfbench::ImageStore store(world.files, "report_files/");
    for (size_t row = 0; row < table.rows.size() && row < 64; ++row) {
      try {
        sdfbench::kept_images(table, row, store);
      } catch (const sdfbench::Error&) {
      }
    }
  } catch (const sdfbench::Error&) {
  }
  for (const fs::directory_entry& e : fs::directory_iterator(world.files)) {
    if (world.allowed.count(e.path().filename().string())) continue;
    std::fprintf(stderr, "FAIL: the report's folder received '%s'\n", e.path().filename().c_str());
    std::abort();
  }
  return 0;
}
