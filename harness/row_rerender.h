#pragma once
// `report --render-missing`: a row that kept no images gets its check frame rendered again from
// the configuration its CSV row records (row_configuration.h), compared with the reference at the
// row's check size. What each re-render measured is listed in the image folder's rendered.csv,
// so writing the page again renders nothing twice; whether it reproduces the row is judged from
// those figures when the page is written.
#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include "harness/benchmark_runner.h"
#include "harness/csv.h"
#include "harness/image_store.h"

namespace sdfbench {

struct Rerender {
  std::string frame, reference, diff;  // hrefs (ImageStore)
  std::string sdfbench;                // the commit that rendered it
  bool reference_row = false;          // the row is the reference backend's own
  // its agreement with the reference, as the CSV writes figures (csv_number; empty: none)
  std::string hit_agreement, id_agreement, psnr, depth_p99, depth_p99_voxels;
};

// Empty when the re-render reproduces the row's agreement figures (those its CSV has): hit and
// id within half a pixel of the check image, PSNR within 0.01 dB (or both above 100 dB, where
// only float rounding differs: no 8-bit pixel does), depth p99 within 0.1 %, depth in voxels
// within 0.001; else what differs, "column row → re-render", comma-separated.
std::string rerender_differences(const CsvTable& table, size_t row, const Rerender& rerender);

class RowRerenderer {
 public:
  static constexpr const char* kListName = "rendered.csv";

  RowRerenderer(ImageStore& store, std::filesystem::path dir, std::string device);
  // Whether this CSV row (file and configuration) was rendered before and its images are still there.
  bool listed(const CsvTable& table, size_t row) const { return find_listed(table, row) != nullptr; }
  // From the list when listed, else rendered now.
  Rerender get(const CsvTable& table, size_t row);
  // Writes the list of the rows got since construction (after every render, also the earlier
  // list's rows not reached yet, so an interrupted report keeps them).
  void write_list(bool keep_unreached) const;

 private:
  const std::vector<std::string>* find_listed(const CsvTable& table, size_t row) const;
  Rerender render(const CsvTable& table, size_t row);

  ImageStore& store_;
  std::filesystem::path dir_;
  std::string device_;
  CsvTable list_, previous_;
  std::map<std::string, std::unique_ptr<BenchmarkRunner>> runners_;  // by reference and check size
};

}  // namespace sdfbench
