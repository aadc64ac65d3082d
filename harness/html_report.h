#pragma once
// The HTML view of measurement CSVs (`sdfbench report`): one page without scripts or anything
// fetched from the network. The environment of every file (device, driver, CPU, threads,
// commits, machine load), the thesis' tables with the thesis' FPS and our ratio to it, the plots,
// and every row with its figures and the thumbnails of its check images (the backend's frame,
// the reference's and their difference map, each a link to the full image). Flagged rows
// (disagreeing, truncated, failed, budget-cut, timed on a busy machine, images not the row's)
// are highlighted and listed at the top.
#include <string>
#include <vector>

#include "harness/csv.h"
#include "harness/thesis_tables.h"

namespace sdfbench {

// A row's images as the page links them (paths relative to the page), or none with `note` saying why.
struct RowImages {
  std::string frame, reference, diff;
  std::string note;        // where the images come from, or why there are none
  bool mismatch = false;   // re-rendered images whose agreement figures are not the row's
};

struct ReportFile {
  CsvTable table;                // its source: the CSV's path as given
  std::vector<RowImages> images;  // one per row
};

struct ReportPlot {
  std::string href, caption;
};

// `generator`: the commit of the sdfbench that writes the page.
std::string html_report(const std::vector<ReportFile>& files, const std::vector<ReportPlot>& plots,
                        const ThesisTables& thesis, const std::string& generator);

}  // namespace sdfbench
