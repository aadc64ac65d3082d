// PNG, JPEG, BMP and TGA (and writing Radiance HDR) through Debian's libstb, from and into memory
// (image_codec.h).
#include <algorithm>
#include <climits>
#include <cmath>
#include <cstring>
#include <memory>
#include <string_view>
#include <utility>

#include <stb_image.h>
#include <stb_image_write.h>

#include "util/error.h"
#include "util/image_codec.h"

namespace sdfbench::codec {
namespace {

const stbi_uc* data_of(std::span<const std::byte> bytes) { return reinterpret_cast<const stbi_uc*>(bytes.data()); }

int length_of(std::span<const std::byte> bytes) {
  if (bytes.size() > static_cast<size_t>(INT_MAX)) throw Error("larger than 2 GiB");
  return static_cast<int>(bytes.size());
}

// After a libstb call that failed (its reason is only fresh then).
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

enum class Format { png, jpeg, bmp, tga };

bool starts_with(std::span<const std::byte> bytes, std::string_view signature) {
  return bytes.size() >= signature.size() && std::memcmp(bytes.data(), signature.data(), signature.size()) == 0;
}

// The format by its signature. libstb tries every decoder it has (GIF, PSD, PIC, PNM too) on any
// bytes; only the documented ones reach it. TGA has no signature: what is left is TGA if
// libstb's TGA header test accepts it, the only test left that can.
Format format_of(std::span<const std::byte> bytes) {
  if (starts_with(bytes, "\x89PNG\r\n\x1a\n")) return Format::png;
  if (starts_with(bytes, "\xff\xd8")) return Format::jpeg;
  if (starts_with(bytes, "BM")) return Format::bmp;
  // libstb's Radiance HDR decoder loops for ever on some truncated files (found by
  // tests/image_codec_test.cpp), so HDR images are written but never read.
  if (stbi_is_hdr_from_memory(data_of(bytes), length_of(bytes)))
    throw Error("Radiance HDR images are not read (libstb's decoder does not stop on every damaged file); convert it to EXR or PNG");
  const std::pair<const char*, const char*> unread[] = {
      {"GIF8", "GIF"}, {"8BPS", "PSD"}, {"\x53\x80\xf6\x34", "PIC"}, {"P5", "PNM"}, {"P6", "PNM"}};
  for (const auto& [signature, name] : unread)
    if (starts_with(bytes, signature))
      throw Error(std::string(name) + " images are not read (textures are PNG, JPEG, BMP, TGA or EXR)");
  return Format::tga;
}

uint64_t le(std::span<const std::byte> bytes, size_t at, int count) {
  uint64_t v = 0;
  for (int k = count - 1; k >= 0; --k) v = (v << 8) | (at + k < bytes.size() ? std::to_integer<uint64_t>(bytes[at + k]) : 0);
  return v;
}

// The fewest bytes a BMP or TGA of this size can be, from its header. libstb reads zeros past the
// end of the data, so a truncated file, or 100 bytes claiming 4096x4096, would decode to an image
// it mostly invented. PNG's decoder fails on missing data itself; JPEG: jpeg_complete().
uint64_t least_bytes(Format format, std::span<const std::byte> bytes, uint64_t width, uint64_t height) {
  if (format == Format::bmp) {  // rows of width * bits, padded to 4 bytes, from the data offset
    const uint64_t header_bytes = le(bytes, 14, 4), bits = le(bytes, header_bytes == 12 ? 24 : 28, 2);
    return le(bytes, 10, 4) + (width * bits + 31) / 32 * 4 * height;
  }
  if (format == Format::tga) {  // 18-byte header, image id, colour map, then pixels, raw or RLE
    const uint64_t pixel_bytes = (le(bytes, 16, 1) + 7) / 8;
    const uint64_t palette = le(bytes, 1, 1) == 1 ? le(bytes, 5, 2) * ((le(bytes, 7, 1) + 7) / 8) : 0;
    const uint64_t pixels = width * height, start = 18 + le(bytes, 0, 1) + palette;
    const bool rle = le(bytes, 2, 1) >= 8;  // an RLE packet holds at most 128 pixels
    return start + (rle ? (pixels + 127) / 128 * (1 + pixel_bytes) : pixels * pixel_bytes);
  }
  return 0;
}

// A JPEG ends its last scan with the end-of-image marker (FF D9). Neither marker can occur inside
// entropy-coded data (an FF there is stuffed as FF 00), so a file whose last start-of-scan (FF DA)
// is not followed by FF D9 was cut short. Needed because Debian 13's libstb decodes such a file
// with zeros for the missing data (Debian 12's fails).
bool jpeg_complete(std::span<const std::byte> bytes) {
  auto byte = [&](size_t i) { return std::to_integer<unsigned>(bytes[i]); };
  size_t last_scan = 0;
  for (size_t i = 0; i + 1 < bytes.size(); ++i)
    if (byte(i) == 0xff && byte(i + 1) == 0xda) last_scan = i;
  for (size_t i = last_scan; last_scan > 0 && i + 1 < bytes.size(); ++i)
    if (byte(i) == 0xff && byte(i + 1) == 0xd9) return true;
  return false;
}

template <typename T>
DecodedImage decode_as(std::span<const std::byte> bytes, ImageHeader header, T* (*load)(const stbi_uc*, int, int*, int*, int*, int),
                       float scale) {
  int w = 0, h = 0, c = 0;
  return copy_scaled(load(data_of(bytes), length_of(bytes), &w, &h, &c, static_cast<int>(header.channels)), header, false, scale);
}

}  // namespace

ImageHeader stb_header(std::span<const std::byte> bytes) {
  const Format format = format_of(bytes);
  int w = 0, h = 0, c = 0;
  // libstb refuses a PNG whose pixels pass 2^30 bytes with "unknown image type": the size its
  // header declares says why.
  if (const auto size = png_declared_size(bytes); size && (size->first > kMaxImageSide || size->second > kMaxImageSide))
    throw Error("a PNG of " + std::to_string(size->first) + "x" + std::to_string(size->second) + " pixels, larger than " +
                std::to_string(kMaxImageSide) + " on a side");
  if (!stbi_info_from_memory(data_of(bytes), length_of(bytes), &w, &h, &c)) fail();
  if (format == Format::bmp && h < 0 && h != INT_MIN) h = -h;  // a top-down BMP (libstb decodes it)
  if (w < 1 || h < 1 || c < 1)
    throw Error("not a readable image: its header says " + std::to_string(w) + "x" + std::to_string(h) + " pixels");
  // (Sides over kMaxImageSide are refused by the caller; below it the product cannot overflow.)
  const uint64_t least = std::max(w, h) > static_cast<int>(kMaxImageSide) ? 0 : least_bytes(format, bytes, uint64_t(w), uint64_t(h));
  if (format == Format::jpeg && !jpeg_complete(bytes))
    throw Error("truncated: the JPEG's last scan has no end-of-image marker (FF D9)");
  if (bytes.size() < least)
    throw Error("truncated or a damaged header: " + std::to_string(w) + "x" + std::to_string(h) +
                " pixels take at least " + std::to_string(least) + " bytes, the file has " + std::to_string(bytes.size()));
  return {static_cast<uint32_t>(w), static_cast<uint32_t>(h), static_cast<uint32_t>(c)};
}

DecodedImage stb_decode(std::span<const std::byte> bytes) {
  const ImageHeader header = stb_header(bytes);
  if (stbi_is_16_bit_from_memory(data_of(bytes), length_of(bytes)))
    return decode_as(bytes, header, stbi_load_16_from_memory, 1.0f / 65535.0f);
  DecodedImage image = decode_as(bytes, header, stbi_load_from_memory, 1.0f / 255.0f);
  if (format_of(bytes) == Format::tga) {
    // An RLE TGA has no length to check and no end marker: decode it again with bytes appended.
    // A decoder that stays inside the file gives the same pixels; one that ran past the end
    // (where libstb reads zeros) now reads 0xff and gives others.
    std::vector<std::byte> padded(bytes.begin(), bytes.end());
    padded.resize(bytes.size() + 64, std::byte{0xff});
    if (decode_as(padded, header, stbi_load_from_memory, 1.0f / 255.0f).pixels != image.pixels)
      throw Error("truncated: its pixel data ends before the " + std::to_string(header.width) + "x" +
                  std::to_string(header.height) + " pixels its header says");
  }
  return image;
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
