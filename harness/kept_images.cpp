#include "harness/kept_images.h"

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>

#include "util/error.h"
#include "util/image_codec.h"

namespace sdfbench {
namespace {

namespace fs = std::filesystem;

// An image column's file: a relative path that stays inside the CSV's folder once symlinks are
// resolved (the report's folder is meant for sharing: nothing else is copied into it).
fs::path image_in_csv_folder(const CsvTable& t, const std::string& name, const std::string& where) {
  const fs::path folder = fs::path(t.source).parent_path().empty() ? fs::path(".") : fs::path(t.source).parent_path();
  std::error_code ec;
  const fs::path base = fs::canonical(folder, ec);
  const fs::path path = ec ? fs::path() : fs::weakly_canonical(base / name, ec);
  const auto [end, _] = std::mismatch(base.begin(), base.end(), path.begin(), path.end());
  if (ec || name.empty() || fs::path(name).is_absolute() || end != base.end())
    throw Error(where + ": '" + name + "' is not a file inside the CSV's folder '" + folder.string() + "'");
  return path;
}

// The row's check size ("320x180"), which its kept images must have.
std::optional<std::pair<uint32_t, uint32_t>> check_size_of(const CsvTable& t, size_t row, const std::string& where) {
  if (!t.has_column("check_size")) return std::nullopt;
  const std::string& text = t.rows[row][t.column("check_size")];
  const size_t x = text.find('x');
  uint32_t width = 0, height = 0;
  const auto number = [&](size_t from, size_t to, uint32_t& value) {
    const auto [end, ec] = std::from_chars(text.data() + from, text.data() + to, value);
    return ec == std::errc() && end == text.data() + to && value >= 1 && value <= kMaxImageSide;
  };
  if (x == std::string::npos || !number(0, x, width) || !number(x + 1, text.size(), height))
    throw Error(where + ": check_size '" + text + "' is not WIDTHxHEIGHT");
  return std::pair{width, height};
}

}  // namespace

RowImages kept_images(const CsvTable& t, size_t row, ImageStore& store) {
  const std::string where = "'" + t.source + "' row " + std::to_string(row + 1);
  const auto size = check_size_of(t, row, where);
  RowImages images;
  for (auto [column, href] : {std::pair{"frame_image", &images.frame}, std::pair{"reference_image", &images.reference},
                              std::pair{"diff_image", &images.diff}}) {
    const std::string name = t.has_column(column) ? t.rows[row][t.column(column)] : std::string();
    *href = store.add_file(image_in_csv_folder(t, name, where + ": " + column), where + ": " + column, size);
  }
  return images;
}

bool kept_images_present(const CsvTable& t, size_t row) {
  const std::string where = "'" + t.source + "' row " + std::to_string(row + 1);
  for (const char* column : {"frame_image", "reference_image", "diff_image"}) {
    const std::string name = t.has_column(column) ? t.rows[row][t.column(column)] : std::string();
    std::error_code ec;
    if (fs::exists(image_in_csv_folder(t, name, where + ": " + column), ec)) return true;
  }
  return false;  // none of the three: not kept here (one or two gone is a broken row: kept_images names it)
}

}  // namespace sdfbench
