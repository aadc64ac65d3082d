// The binary's image codecs (util/image_codec.h) and colour metrics (harness/image_agreement.h)
// against OpenImageIO, an independent reader and comparer.
#include <cmath>
#include <cstring>
#include <random>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "harness/image_agreement.h"
#include "harness/image_output.h"
#include "renderers/shading/gpu_types.h"
#include "tests/test_support.h"
#include "util/error.h"
#include "util/image_codec.h"
#include "util/input_file.h"

namespace sdfbench {
namespace {

FrameImages random_frame(uint32_t w, uint32_t h, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  FrameImages f;
  f.width = w;
  f.height = h;
  const size_t n = size_t(w) * h;
  for (size_t i = 0; i < n; ++i) {
    f.color.emplace_back(unit(rng), unit(rng), unit(rng), 1.0f);
    f.depth.push_back(1.0f + 10.0f * unit(rng));
    f.instance_id.push_back(i % 7 == 0 ? shading::NO_INSTANCE_VALUE : static_cast<uint32_t>(i % 5));
    f.primitive_id.push_back(static_cast<uint32_t>(i));
    f.normal.emplace_back(0.0f, 1.0f, 0.0f);
  }
  return f;
}

std::vector<float> read_with_oiio(const std::filesystem::path& path, OIIO::ImageSpec& spec) {
  auto in = OIIO::ImageInput::open(path.string());
  if (!in) return {};
  spec = in->spec();
  std::vector<float> pixels(size_t(spec.width) * spec.height * spec.nchannels);
  in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data());
  return pixels;
}

OIIO::ImageBuf rgb_buffer(const FrameImages& f) {
  OIIO::ImageBuf buf(OIIO::ImageSpec(int(f.width), int(f.height), 3, OIIO::TypeDesc::FLOAT));
  std::vector<float> rgb;
  for (const glm::vec4& c : f.color) rgb.insert(rgb.end(), {c.x, c.y, c.z});
  buf.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, rgb.data());
  return buf;
}

// Mean error, RMS, PSNR and the failed-pixel count are OpenImageIO compare's, on frames that
// differ everywhere by random amounts (some pixels over the 0.05 threshold, some under).
TEST(ImageCodec, ColourMetricsMatchOpenImageIOCompare) {
  for (uint32_t seed : {1u, 2u, 3u}) {
    const FrameImages ref = random_frame(37, 23, seed);
    FrameImages test = ref;
    std::mt19937 rng(seed + 100);
    std::normal_distribution<float> noise(0.0f, 0.03f);
    // Frames hold display-encoded colours in [0, 1] (the PSNR's peak of 1).
    for (glm::vec4& c : test.color)
      c = glm::vec4(glm::clamp(c.x + noise(rng), 0.0f, 1.0f), glm::clamp(c.y + noise(rng), 0.0f, 1.0f), c.z, c.w);
    const Agreement g = compare_frames(test, ref);
    const auto stats = OIIO::ImageBufAlgo::compare(rgb_buffer(test), rgb_buffer(ref), kPixelFailThreshold, kPixelFailThreshold);
    EXPECT_NEAR(g.mean_error, stats.meanerror, 1e-9);
    EXPECT_NEAR(g.rms_error, stats.rms_error, 1e-9);
    EXPECT_NEAR(g.psnr, stats.PSNR, 1e-6);
    EXPECT_GT(stats.nfail, 0u);
    EXPECT_NEAR(g.over_threshold_percent, 100.0 * double(stats.nfail) / double(ref.color.size()), 1e-9);
  }
}

// What the writers write, OpenImageIO reads back: 8-bit formats within rounding (JPEG within its
// loss), float formats exactly (HDR within its shared-exponent precision).
TEST(ImageCodec, WrittenImagesReadBackWithOpenImageIO) {
  test::TempDir dir;
  const FrameImages frame = random_frame(19, 11, 7);
  const std::vector<std::pair<std::string, double>> cases = {
      {"png", 0.5 / 255 + 1e-6}, {"bmp", 0.5 / 255 + 1e-6}, {"tga", 0.5 / 255 + 1e-6}, {"exr", 0.0}, {"hdr", 0.01}, {"jpg", 0.5}};
  for (const auto& [ext, tolerance] : cases) {
    SCOPED_TRACE(ext);
    const auto path = dir.path() / ("a." + ext);
    write_color_image(frame, path);
    OIIO::ImageSpec spec;
    const std::vector<float> pixels = read_with_oiio(path, spec);
    ASSERT_EQ(spec.width, 19);
    ASSERT_EQ(spec.height, 11);
    ASSERT_GE(spec.nchannels, 3);
    double worst = 0, sum = 0;
    for (size_t i = 0; i < frame.color.size(); ++i)
      for (int c = 0; c < 3; ++c) {
        const double e = std::abs(pixels[i * spec.nchannels + c] - frame.color[i][c]);
        worst = std::max(worst, e);
        sum += e;
      }
    if (ext == "jpg")
      EXPECT_LT(sum / (3.0 * double(frame.color.size())), 0.1);  // random noise is JPEG's worst case
    else
      EXPECT_LE(worst, tolerance);
  }
}

TEST(ImageCodec, AovChannelsReadBackByName) {
  test::TempDir dir;
  const FrameImages frame = random_frame(9, 5, 3);
  const auto path = dir.path() / "aov.exr";
  write_aov_image(frame, path);
  auto in = OIIO::ImageInput::open(path.string());
  ASSERT_TRUE(in);
  const OIIO::ImageSpec spec = in->spec();
  ASSERT_EQ(spec.nchannels, 7);
  std::vector<float> pixels(size_t(spec.width) * spec.height * 7);
  ASSERT_TRUE(in->read_image(0, 0, 0, 7, OIIO::TypeDesc::FLOAT, pixels.data()));
  const int depth = spec.channelindex("depth"), id = spec.channelindex("instance_id"), prim = spec.channelindex("primitive_id");
  ASSERT_GE(depth, 0);
  for (size_t i = 0; i < frame.depth.size(); ++i) {
    EXPECT_EQ(pixels[i * 7 + depth], frame.depth[i]);
    EXPECT_EQ(pixels[i * 7 + id], frame.instance_id[i] == shading::NO_INSTANCE_VALUE ? -1.0f : float(frame.instance_id[i]));
    EXPECT_EQ(pixels[i * 7 + prim], frame.instance_id[i] == shading::NO_INSTANCE_VALUE ? -1.0f : float(frame.primitive_id[i]));
  }
}

// Damaged input is an Error naming the image, never a crash or a hang (nor an image libstb made up
// from the zeros it reads past the end): truncated files of each format,
// random bytes, and an EXR whose header declares a data window beyond the size limit.
TEST(ImageCodec, DamagedFilesAreErrorsNamingTheImage) {
  test::TempDir dir;
  const FrameImages frame = random_frame(16, 16, 5);
  for (const char* ext : {"png", "exr", "jpg", "hdr", "bmp", "tga"}) {
    SCOPED_TRACE(ext);
    const auto path = dir.path() / (std::string("d.") + ext);
    write_color_image(frame, path);
    const std::vector<std::byte> bytes = read_input_bytes(path, "image", 1u << 30);
    for (size_t keep : {size_t(0), size_t(3), size_t(40), bytes.size() / 3, bytes.size() / 2, bytes.size() - 5, bytes.size()}) {
      const std::span<const std::byte> cut(bytes.data(), keep);
      try {
        const DecodedImage image = decode_image(cut, "image 'd'");
        EXPECT_EQ(keep, bytes.size()) << "a truncated file decoded";
        EXPECT_EQ(image.pixels.size(), size_t(image.header.width) * image.header.height * image.header.channels);
      } catch (const Error& e) {
        EXPECT_TRUE(keep < bytes.size() || std::string(ext) == "hdr") << e.what();
        EXPECT_NE(std::string(e.what()).find("cannot read image 'd'"), std::string::npos) << e.what();
      }
    }
  }
  std::mt19937 rng(9);
  std::vector<std::byte> noise(4096);
  for (std::byte& b : noise) b = std::byte(rng() & 0xff);
  EXPECT_THROW(decode_image(noise, "image 'n'"), Error);
  noise[0] = std::byte(0x76), noise[1] = std::byte(0x2f), noise[2] = std::byte(0x31), noise[3] = std::byte(0x01);  // EXR magic
  EXPECT_THROW(decode_image(noise, "image 'n'"), Error);
}

std::vector<std::byte> as_bytes(const std::string& s) {
  const auto* p = reinterpret_cast<const std::byte*>(s.data());
  return {p, p + s.size()};
}

std::string decode_error(const std::vector<std::byte>& bytes) {
  try {
    decode_image(bytes, "image 'x'");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

std::vector<std::byte> encoded(uint32_t w, uint32_t h, ImageFormat format, uint32_t seed) {
  std::mt19937 rng(seed);
  FloatImage image{w, h, {"R", "G", "B"}, {}};
  for (size_t i = 0; i < size_t(w) * h * 3; ++i) image.pixels.push_back(float(rng() % 256) / 255.0f);
  const std::vector<unsigned char> bytes = encode_image(image, format, "'x'");
  const auto* p = reinterpret_cast<const std::byte*>(bytes.data());
  return {p, p + bytes.size()};
}

// An uncompressed 24-bit TGA (libstb's writer compresses).
std::vector<std::byte> raw_tga(uint32_t w, uint32_t h) {
  std::string t(18, '\0');
  t[2] = 2;  // true colour, uncompressed
  t[12] = char(w), t[13] = char(w >> 8), t[14] = char(h), t[15] = char(h >> 8), t[16] = 24;
  for (uint32_t i = 0; i < w * h * 3; ++i) t += char(i * 7);
  return as_bytes(t);
}

// GIF and PNM decode in libstb, but are no documented texture format; each is refused by name.
TEST(ImageCodec, UndocumentedFormatsAreRefusedByName) {
  const std::string gif("GIF89a\x01\x00\x01\x00\x80\x00\x00\xff\xff\xff\x00\x00\x00,\x00\x00\x00\x00\x01\x00\x01\x00\x00\x02\x02" "D\x01\x00;", 35);
  const std::string pnm = "P6\n2 1\n255\n" + std::string(6, '\x80');
  for (const auto& [bytes, name] : {std::pair{gif, "GIF"}, std::pair{pnm, "PNM"}, std::pair{std::string("8BPS") + std::string(40, '\1'), "PSD"}}) {
    const std::string e = decode_error(as_bytes(bytes));
    EXPECT_NE(e.find(std::string("cannot read image 'x': ") + name), std::string::npos) << e;
    EXPECT_NE(e.find("not read (textures are PNG, JPEG, BMP, TGA or EXR)"), std::string::npos) << e;
  }
}

// BMP and TGA have no end marker, and libstb reads zeros past the end: a truncated file (every
// cut) or a header claiming more pixels than the file holds is an error, before decoding where
// the header says enough.
TEST(ImageCodec, TruncatedBmpAndTgaAreErrors) {
  const std::vector<std::pair<std::string, std::vector<std::byte>>> files = {
      {"bmp", encoded(13, 7, ImageFormat::bmp, 1)}, {"rle tga", encoded(13, 7, ImageFormat::tga, 2)}, {"raw tga", raw_tga(13, 7)}};
  for (const auto& [name, bytes] : files) {
    SCOPED_TRACE(name);
    EXPECT_EQ(decode_image(bytes, "image 'x'").pixels.size(), 13u * 7 * 3);
    const size_t header = name == "bmp" ? 54 : 18;
    for (size_t keep = 0; keep < bytes.size(); ++keep) {
      const std::string e = decode_error({bytes.begin(), bytes.begin() + long(keep)});
      if (keep < header)  // a cut header: any error
        EXPECT_NE(e.find("cannot read image 'x': "), std::string::npos) << keep << ": " << e;
      else
        EXPECT_NE(e.find("cannot read image 'x': truncated"), std::string::npos) << keep << " of " << bytes.size() << ": " << e;
    }
  }
  // 100 bytes claiming 4096x4096 are refused from the header alone (read_image_header).
  for (std::vector<std::byte> bytes : {encoded(2, 2, ImageFormat::bmp, 3), raw_tga(2, 2), encoded(2, 2, ImageFormat::tga, 4)}) {
    if (bytes[0] == std::byte{'B'})
      bytes[18] = bytes[22] = std::byte{0}, bytes[19] = bytes[23] = std::byte{0x10};
    else
      bytes[12] = bytes[14] = std::byte{0}, bytes[13] = bytes[15] = std::byte{0x10};
    bytes.resize(100);
    try {
      read_image_header(bytes, "image 'x'");
      ADD_FAILURE() << "a 100-byte file claiming 4096x4096 passed";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("4096x4096 pixels take at least"), std::string::npos) << e.what();
    }
  }
}

// A negative BMP height means rows stored top-down: decoded, as the same image.
TEST(ImageCodec, TopDownBmpDecodes) {
  const std::vector<std::byte> up = encoded(5, 3, ImageFormat::bmp, 5);
  std::vector<std::byte> down = up;
  const uint32_t offset = std::to_integer<uint32_t>(up[10]), stride = 16;  // 5 pixels * 3 bytes, padded to 4
  for (uint32_t row = 0; row < 3; ++row)
    std::copy_n(up.begin() + offset + row * stride, stride, down.begin() + offset + (2 - row) * stride);
  const int32_t height = -3;
  std::memcpy(down.data() + 22, &height, 4);
  EXPECT_EQ(decode_image(down, "image 'x'").pixels, decode_image(up, "image 'x'").pixels);
}

TEST(ImageCodec, FormatsByExtension) {
  EXPECT_EQ(image_format_of("a.PNG"), ImageFormat::png);
  EXPECT_EQ(image_format_of("a.jpeg"), ImageFormat::jpeg);
  EXPECT_EQ(image_format_of("dir.exr/a.Exr"), ImageFormat::exr);
  EXPECT_FALSE(image_format_of("a.tif"));
  EXPECT_FALSE(image_format_of("png"));
  FloatImage seven{2, 1, {"a", "b", "c", "d", "e", "f", "g"}, std::vector<float>(14, 0.5f)};
  EXPECT_EQ(encode_image(seven, ImageFormat::exr, "'x.exr'").empty(), false);
  try {
    encode_image(seven, ImageFormat::png, "'x.png'");
    ADD_FAILURE() << "7 channels written as PNG";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("need an EXR file"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sdfbench

namespace sdfbench {
namespace {

// A PNG whose header declares 100000 x 100000 (libstb's "unknown image type") says its size.
TEST(ImageCodec, AHugePngHeaderSaysItsSize) {
  const unsigned char header[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13, 'I', 'H', 'D', 'R',
                                  0, 1, 0x86, 0xa0, 0, 1, 0x86, 0xa0, 8, 2, 0, 0, 0, 0, 0, 0, 0};
  try {
    read_image_header(std::as_bytes(std::span(header)), "image 'huge.png'");
    ADD_FAILURE() << "a 100000 x 100000 header was read";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "cannot read image 'huge.png': a PNG of 100000x100000 pixels, larger than 16384 on a side");
  }
}

}  // namespace
}  // namespace sdfbench
