// PNG, JPEG, BMP and TGA (and writing Radiance HDR) through Debian's libstb, from and into memory
// (image_codec.h).
#include <algorithm>
#include <climits>
#include <cmath>
#include <memory>

#include <stb_image.h>
#include <stb_image_write.h>

#include "scenes/error.h"
#include "util/image_codec.h"

namespace sdfbench::codec {
namespace {

const stbi_uc* data_of(std::span<const std::byte> bytes) { return reinterpret_cast<const stbi_uc*>(bytes.data()); }

int length_of(std::span<const std::byte> bytes) {
  if (bytes.size() > static_cast<size_t>(INT_MAX)) throw Error("larger than 2 GiB");
  return static_cast<int>(bytes.size());
}

[[noreturn]] void fail() {
  const char* reason = stbi_failure_reason();
  const std::string what = "not a readable PNG, JPEG, BMP, TGA or EXR image";
  throw Error(reason ? what + " (libstb: " + reason + ")" : what);
}

void append(void* context, void* data, int size) {
  auto* out = static_cast<std::vector<unsigned char>*>(context);
  out->insert(out->end(), static_cast<unsigned char*>(data), static_cast<unsigned char*>(data) + size);
}

template <typename T>
DecodedImage copy_scaled(T* raw, ImageHeader header, bool linear, float scale) {
  if (!raw) fail();
  const std::unique_ptr<T, void (*)(void*)> owned(raw, stbi_image_free);
  DecodedImage image{header, linear, {}};
  const size_t count = size_t(header.width) * header.height * header.channels;
  image.pixels.resize(count);
  for (size_t i = 0; i < count; ++i) image.pixels[i] = static_cast<float>(raw[i]) * scale;
  return image;
}

}  // namespace

ImageHeader stb_header(std::span<const std::byte> bytes) {
  // libstb's Radiance HDR decoder loops for ever on some truncated files (found by
  // tests/image_codec_test.cpp), so HDR images are written but never read.
  if (stbi_is_hdr_from_memory(data_of(bytes), length_of(bytes)))
    throw Error("Radiance HDR images are not read (libstb's decoder does not stop on every damaged file); convert it to EXR or PNG");
  int w = 0, h = 0, c = 0;
  if (!stbi_info_from_memory(data_of(bytes), length_of(bytes), &w, &h, &c) || w < 1 || h < 1 || c < 1) fail();
  return {static_cast<uint32_t>(w), static_cast<uint32_t>(h), static_cast<uint32_t>(c)};
}

DecodedImage stb_decode(std::span<const std::byte> bytes) {
  const ImageHeader header = stb_header(bytes);
  const int length = length_of(bytes);
  int w = 0, h = 0, c = 0;
  const int channels = static_cast<int>(header.channels);
  if (stbi_is_16_bit_from_memory(data_of(bytes), length))
    return copy_scaled(stbi_load_16_from_memory(data_of(bytes), length, &w, &h, &c, channels), header, false, 1.0f / 65535.0f);
  return copy_scaled(stbi_load_from_memory(data_of(bytes), length, &w, &h, &c, channels), header, false, 1.0f / 255.0f);
}

std::vector<unsigned char> stb_encode(const FloatImage& image, ImageFormat format) {
  const int w = static_cast<int>(image.width), h = static_cast<int>(image.height);
  const int c = static_cast<int>(image.channel_names.size());
  std::vector<unsigned char> out;
  int ok = 0;
  if (format == ImageFormat::hdr) {
    ok = stbi_write_hdr_to_func(append, &out, w, h, c, image.pixels.data());
  } else {
    std::vector<unsigned char> bytes(image.pixels.size());
    std::transform(image.pixels.begin(), image.pixels.end(), bytes.begin(), [](float v) {
      return static_cast<unsigned char>(std::lround(std::clamp(std::isnan(v) ? 0.0f : v, 0.0f, 1.0f) * 255.0f));
    });
    switch (format) {
      case ImageFormat::png: ok = stbi_write_png_to_func(append, &out, w, h, c, bytes.data(), w * c); break;
      case ImageFormat::jpeg: ok = stbi_write_jpg_to_func(append, &out, w, h, c, bytes.data(), 95); break;
      case ImageFormat::bmp: ok = stbi_write_bmp_to_func(append, &out, w, h, c, bytes.data()); break;
      case ImageFormat::tga: ok = stbi_write_tga_to_func(append, &out, w, h, c, bytes.data()); break;
      default: break;
    }
  }
  if (!ok || out.empty()) throw Error("the encoder failed");
  return out;
}

}  // namespace sdfbench::codec
