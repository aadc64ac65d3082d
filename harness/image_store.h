#pragma once
// The report's image folder: each image stored once under the digest of its bytes, so a
// reference that many rows share (and a frame equal to it) costs its bytes once.
#include <filesystem>
#include <set>
#include <span>
#include <string>

#include "util/image_codec.h"

namespace sdfbench {

class ImageStore {
 public:
  // `dir` exists; `href_prefix` is how the page reaches it ("report_files/").
  ImageStore(std::filesystem::path dir, std::string href_prefix) : dir_(std::move(dir)), prefix_(std::move(href_prefix)) {}

  // Each returns the image's href.
  std::string add(std::span<const std::byte> png);
  std::string add(const FloatImage& image);  // encoded as PNG
  // A PNG file (Error naming `what` and the path when unreadable or not a PNG).
  std::string add_file(const std::filesystem::path& path, const std::string& what);
  // The folder's file for an href this store returned, or empty for any other text.
  std::filesystem::path file_of(const std::string& href) const;

  // Where the folder holds kOwnerMarker (sdfbench made it): removes the PNGs not added since construction.
  void remove_unlinked() const;
  static constexpr const char* kOwnerMarker = ".sdfbench-report";

 private:
  std::filesystem::path dir_;
  std::string prefix_;
  std::set<std::string> names_;
};

}  // namespace sdfbench
