#pragma once
// Image files in memory: decoded from bytes that util/input_file.h read, encoded into bytes that
// util/atomic_file.h writes, so no image library ever opens a path itself. PNG, JPEG, BMP and TGA
// (and writing Radiance HDR) go through Debian's libstb (stb_image, stb_image_write), EXR through OpenEXR:
// two small libraries, which keeps the binary's library closure small enough to carry to a
// machine that cannot install anything (harness/scripts/make_bundle.sh).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace sdfbench {

enum class ImageFormat { png, jpeg, bmp, tga, hdr, exr };

// By extension, case-insensitive (".png", ".jpg"/".jpeg", ".bmp", ".tga", ".hdr", ".exr").
std::optional<ImageFormat> image_format_of(const std::filesystem::path& path);
inline constexpr const char* kImageExtensions = ".png, .exr, .jpg, .hdr, .bmp or .tga";

// The largest side decode_image decodes (16384^2 RGBA floats are 4 GiB; a damaged header allocates
// nothing larger): OpenEXR is told so before it reads a header.
inline constexpr uint32_t kMaxImageSide = 16384;

// What a file's header says, read before any pixel is decoded.
struct ImageHeader {
  uint32_t width = 0, height = 0, channels = 0;
};

// Interleaved float pixels. Integer formats are scaled to [0, 1] and stay display-encoded
// (`linear` false); EXR is as stored (`linear` true).
struct DecodedImage {
  ImageHeader header;
  bool linear = false;
  std::vector<float> pixels;  // width * height * channels, top row first
};

// Both throw Error("cannot read <name>: <reason>") for a file no codec can read. The format is
// found from the bytes' signature, not the name: PNG, JPEG, BMP, TGA or EXR (its R, G, B or Y
// channels); Radiance HDR, GIF, PSD, PIC and PNM (which libstb would decode) are refused (see
// stb_codec.cpp), and so is a BMP or TGA shorter than its header's size needs, or truncated.
ImageHeader read_image_header(std::span<const std::byte> bytes, const std::string& name);

// The width and height a PNG's IHDR chunk declares (the signature and the chunk that must follow
// it checked), read without decoding anything; nothing for bytes that do not start so.
std::optional<std::pair<uint32_t, uint32_t>> png_declared_size(std::span<const std::byte> bytes);
DecodedImage decode_image(std::span<const std::byte> bytes, const std::string& name);

// Interleaved float pixels to encode; `channel_names` (one per channel) name EXR channels.
struct FloatImage {
  uint32_t width = 0, height = 0;
  std::vector<std::string> channel_names;
  std::vector<float> pixels;
};

// EXR stores 32-bit floats with any number of channels; the other formats take 1 to 4 channels,
// HDR as floats, the rest as 8 bits (clamped to [0, 1], rounded). Throws Error naming `name`.
std::vector<unsigned char> encode_image(const FloatImage& image, ImageFormat format, const std::string& name);

// The codecs behind decode_image and encode_image.
namespace codec {
bool is_exr(std::span<const std::byte> bytes);
ImageHeader exr_header(std::span<const std::byte> bytes);
DecodedImage exr_decode(std::span<const std::byte> bytes);
std::vector<unsigned char> exr_encode(const FloatImage& image);
ImageHeader stb_header(std::span<const std::byte> bytes);
DecodedImage stb_decode(std::span<const std::byte> bytes);
std::vector<unsigned char> stb_encode(const FloatImage& image, ImageFormat format);
}  // namespace codec

}  // namespace sdfbench
