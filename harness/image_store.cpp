#include "harness/image_store.h"

#include <cstdio>
#include <fstream>

#include "util/atomic_file.h"
#include "util/error.h"
#include "util/fnv1a.h"
#include "util/input_file.h"

namespace sdfbench {

namespace fs = std::filesystem;

namespace {
constexpr uint64_t kMaxImageBytes = uint64_t{64} << 20;
}

ImageStore::ImageStore(fs::path dir, std::string href_prefix) : dir_(std::move(dir)), prefix_(std::move(href_prefix)) {
  std::ifstream marker(dir_ / kOwnerMarker);
  for (std::string name; std::getline(marker, name);)
    if (name.size() == 20 && name.ends_with(".png") && name.find('/') == std::string::npos) written_.insert(name);
}

std::string ImageStore::add(std::span<const std::byte> png) {
  char name[32];
  std::snprintf(name, sizeof name, "%016llx.png", static_cast<unsigned long long>(fnv1a64(png)));
  if (names_.insert(name).second && !fs::exists(dir_ / name)) {
    write_file_atomically(dir_ / name, png);
    written_.insert(name);
  }
  return prefix_ + name;
}

std::string ImageStore::add(const FloatImage& image) {
  const std::vector<unsigned char> png = encode_image(image, ImageFormat::png, "report image");
  return add(std::as_bytes(std::span(png.data(), png.size())));
}

std::string ImageStore::add_file(const fs::path& path, const std::string& what,
                                 std::optional<std::pair<uint32_t, uint32_t>> size) {
  const std::vector<std::byte> bytes = read_input_bytes(path, what, kMaxImageBytes);
  const auto declared = png_declared_size(bytes);
  if (!declared || bytes.size() < 33) throw Error(what + " '" + path.string() + "' is not a PNG image");
  const auto [width, height] = *declared;
  if (size ? (width != size->first || height != size->second)
           : (width == 0 || height == 0 || width > kMaxImageSide || height > kMaxImageSide))
    throw Error(what + " '" + path.string() + "' declares " + std::to_string(width) + "x" + std::to_string(height) + " pixels, " +
                (size ? "not the row's check size " + std::to_string(size->first) + "x" + std::to_string(size->second)
                      : "more than " + std::to_string(kMaxImageSide) + " a side"));
  return add(bytes);
}

fs::path ImageStore::file_of(const std::string& href) const {
  if (href.rfind(prefix_, 0) != 0 || href.find('/', prefix_.size()) != std::string::npos) return {};
  return dir_ / href.substr(prefix_.size());
}

void ImageStore::remove_unlinked() const {
  std::string list;
  for (const std::string& name : written_) {
    if (names_.count(name)) list += name + "\n";
    else if (fs::is_regular_file(fs::symlink_status(dir_ / name))) fs::remove(dir_ / name);
  }
  write_file_atomically(dir_ / kOwnerMarker, std::as_bytes(std::span(list.data(), list.size())));
}

}  // namespace sdfbench
