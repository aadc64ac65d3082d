#include "harness/image_store.h"

#include <cstdio>
#include <cstring>

#include "util/atomic_file.h"
#include "util/error.h"
#include "util/fnv1a.h"
#include "util/input_file.h"

namespace sdfbench {

namespace fs = std::filesystem;

namespace {
constexpr uint64_t kMaxImageBytes = uint64_t{64} << 20;
}

std::string ImageStore::add(std::span<const std::byte> png) {
  char name[32];
  std::snprintf(name, sizeof name, "%016llx.png", static_cast<unsigned long long>(fnv1a64(png)));
  if (names_.insert(name).second && !fs::exists(dir_ / name)) write_file_atomically(dir_ / name, png);
  return prefix_ + name;
}

std::string ImageStore::add(const FloatImage& image) {
  const std::vector<unsigned char> png = encode_image(image, ImageFormat::png, "report image");
  return add(std::as_bytes(std::span(png.data(), png.size())));
}

std::string ImageStore::add_file(const fs::path& path, const std::string& what) {
  const std::vector<std::byte> bytes = read_input_bytes(path, what, kMaxImageBytes);
  static const unsigned char magic[] = {0x89, 'P', 'N', 'G'};
  if (bytes.size() < 4 || std::memcmp(bytes.data(), magic, 4) != 0) throw Error(what + " '" + path.string() + "' is not a PNG image");
  return add(bytes);
}

fs::path ImageStore::file_of(const std::string& href) const {
  if (href.rfind(prefix_, 0) != 0 || href.find('/', prefix_.size()) != std::string::npos) return {};
  return dir_ / href.substr(prefix_.size());
}

void ImageStore::remove_unlinked() const {
  if (!fs::exists(dir_ / kOwnerMarker)) return;
  for (const fs::directory_entry& e : fs::directory_iterator(dir_))
    if (e.is_regular_file() && e.path().extension() == ".png" && !names_.count(e.path().filename().string())) fs::remove(e.path());
}

}  // namespace sdfbench
