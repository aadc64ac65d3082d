#pragma once
// A row's kept check images (table/sweep --keep-images) as the report takes them: each image
// column's file resolved inside the CSV's folder (absolute paths, .. and symlinks out of it are
// refused: the report's folder is meant for sharing), its PNG header checked against the row's
// check size, then copied into the report's image store.
#include <cstddef>

#include "harness/csv.h"
#include "harness/html_report.h"
#include "harness/image_store.h"

namespace sdfbench {

// The row's frame, reference and difference images as the page links them. Throws Error naming
// the CSV, the row and the column.
RowImages kept_images(const CsvTable& table, size_t row, ImageStore& store);

// Whether any of the row's three image files is there (a committed snapshot keeps its report's copies,
// not the run's kept images: `report --render-missing` renders those again). Throws Error as
// kept_images() does for a path outside the CSV's folder.
bool kept_images_present(const CsvTable& table, size_t row);

}  // namespace sdfbench
