#pragma once
// The report's image folder: each image stored once under the digest of its bytes, so a
// reference that many rows share (and a frame equal to it) costs its bytes once.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <utility>
#include <set>
#include <span>
#include <string>

#include "util/image_codec.h"

namespace sdfbench {

class ImageStore {
 public:
  // `dir` exists; `href_prefix` is how the page reaches it ("report_files/"). The images an
  // earlier report wrote there are read from kOwnerMarker's list.
  ImageStore(std::filesystem::path dir, std::string href_prefix);

  // Each returns the image's href.
  std::string add(std::span<const std::byte> png);
  std::string add(const FloatImage& image);  // encoded as PNG
  // A PNG file (Error naming `what` and the path when unreadable or not a PNG), whose header
  // declares `size` (a row's check size; none: at most kMaxImageSide a side), checked before the
  // file is copied.
  std::string add_file(const std::filesystem::path& path, const std::string& what,
                       std::optional<std::pair<uint32_t, uint32_t>> size = std::nullopt);
  // The folder's file for an href this store returned, or empty for any other text.
  std::filesystem::path file_of(const std::string& href) const;

  // Removes the PNGs a report wrote here (listed in kOwnerMarker) that the new page does not
  // link, and lists the ones it does; any other file is left alone.
  void remove_unlinked() const;
  // Marks a folder as a report's image folder (the names of the images it wrote, one a line).
  static constexpr const char* kOwnerMarker = ".sdfbench-report";

 private:
  std::filesystem::path dir_;
  std::string prefix_;
  std::set<std::string> names_;     // linked by this page
  std::set<std::string> written_;   // written by a report: earlier ones (the marker's list) and this one
};

}  // namespace sdfbench
