#include "util/image_codec.h"

#include <cstring>

#include <cctype>
#include <exception>

#include "util/error.h"


namespace sdfbench {
namespace {

// Runs a codec call; its failure (Error, an OpenEXR exception, bad_alloc) becomes one Error.
template <typename F>
auto guarded(const std::string& what, F&& call) {
  try {
    return call();
  } catch (const std::exception& e) {
    throw Error(what + ": " + e.what());
  }
}

}  // namespace

std::optional<ImageFormat> image_format_of(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".png") return ImageFormat::png;
  if (ext == ".jpg" || ext == ".jpeg") return ImageFormat::jpeg;
  if (ext == ".bmp") return ImageFormat::bmp;
  if (ext == ".tga") return ImageFormat::tga;
  if (ext == ".hdr") return ImageFormat::hdr;
  if (ext == ".exr") return ImageFormat::exr;
  return std::nullopt;
}

ImageHeader read_image_header(std::span<const std::byte> bytes, const std::string& name) {
  return guarded("cannot read " + name, [&] { return codec::is_exr(bytes) ? codec::exr_header(bytes) : codec::stb_header(bytes); });
}

std::optional<std::pair<uint32_t, uint32_t>> png_declared_size(std::span<const std::byte> bytes) {
  // The 8-byte signature, then IHDR's length (13) and type; width and height follow, big-endian.
  static const unsigned char start[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13, 'I', 'H', 'D', 'R'};
  if (bytes.size() < 24 || std::memcmp(bytes.data(), start, sizeof start) != 0) return std::nullopt;
  const auto word = [&](size_t at) {
    uint32_t v = 0;
    for (size_t i = 0; i < 4; ++i) v = v << 8 | std::to_integer<uint32_t>(bytes[at + i]);
    return v;
  };
  return std::pair{word(16), word(20)};
}

DecodedImage decode_image(std::span<const std::byte> bytes, const std::string& name) {
  const ImageHeader header = read_image_header(bytes, name);
  if (header.width > kMaxImageSide || header.height > kMaxImageSide)
    throw Error("cannot read " + name + ": " + std::to_string(header.width) + "x" + std::to_string(header.height) +
                " is larger than " + std::to_string(kMaxImageSide) + " on a side");
  return guarded("cannot read " + name, [&] { return codec::is_exr(bytes) ? codec::exr_decode(bytes) : codec::stb_decode(bytes); });
}

std::vector<unsigned char> encode_image(const FloatImage& image, ImageFormat format, const std::string& name) {
  const size_t channels = image.channel_names.size();
  if (image.width < 1 || image.height < 1 || channels < 1 ||
      image.pixels.size() != size_t(image.width) * image.height * channels)
    throw InternalError("an image to encode has no pixels or the wrong number of values");
  if (format != ImageFormat::exr && channels > 4)
    throw Error("cannot write " + name + ": " + std::to_string(channels) + " channels need an EXR file (use .exr)");
  return guarded("cannot write " + name, [&] { return format == ImageFormat::exr ? codec::exr_encode(image) : codec::stb_encode(image, format); });
}

}  // namespace sdfbench
