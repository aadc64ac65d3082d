// EXR through OpenEXR, from and into memory (image_codec.h).
#include <algorithm>
#include <cstring>
#include <mutex>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfVersion.h>
#include <Iex.h>

#include "util/error.h"
#include "util/image_codec.h"

namespace sdfbench::codec {
namespace {

class MemoryInput : public Imf::IStream {
 public:
  explicit MemoryInput(std::span<const std::byte> bytes) : Imf::IStream("memory"), bytes_(bytes) {}
  bool read(char c[], int n) override {
    if (n < 0 || static_cast<uint64_t>(n) > bytes_.size() - position_) throw Iex::InputExc("unexpected end of file");
    std::memcpy(c, bytes_.data() + position_, static_cast<size_t>(n));
    position_ += static_cast<uint64_t>(n);
    return position_ < bytes_.size();
  }
  uint64_t tellg() override { return position_; }
  void seekg(uint64_t position) override { position_ = std::min<uint64_t>(position, bytes_.size()); }

 private:
  std::span<const std::byte> bytes_;
  uint64_t position_ = 0;
};

class MemoryOutput : public Imf::OStream {
 public:
  MemoryOutput() : Imf::OStream("memory") {}
  void write(const char c[], int n) override {
    if (position_ + static_cast<size_t>(n) > bytes_.size()) bytes_.resize(position_ + static_cast<size_t>(n));
    std::memcpy(bytes_.data() + position_, c, static_cast<size_t>(n));
    position_ += static_cast<size_t>(n);
  }
  uint64_t tellp() override { return position_; }
  void seekp(uint64_t position) override { position_ = static_cast<size_t>(position); }
  std::vector<unsigned char> take() { return std::move(bytes_); }

 private:
  std::vector<unsigned char> bytes_;
  size_t position_ = 0;
};

// OpenEXR refuses larger data windows itself, before it allocates anything for them.
void limit_sizes() {
  static std::once_flag once;
  std::call_once(once, [] {
    Imf::Header::setMaxImageSize(int(kMaxImageSide), int(kMaxImageSide));
    Imf::Header::setMaxTileSize(int(kMaxImageSide), int(kMaxImageSide));
  });
}

// R, G, B when the file has them all, else Y (luminance): what a texture reads.
std::vector<std::string> colour_channels(const Imf::Header& header) {
  const Imf::ChannelList& channels = header.channels();
  if (channels.findChannel("R") && channels.findChannel("G") && channels.findChannel("B")) return {"R", "G", "B"};
  if (channels.findChannel("Y")) return {"Y"};
  throw Error("an EXR image without R, G, B or Y channels");
}

ImageHeader header_of(const Imf::InputFile& file) {
  const Imath::Box2i window = file.header().dataWindow();
  return {static_cast<uint32_t>(window.max.x - window.min.x + 1), static_cast<uint32_t>(window.max.y - window.min.y + 1),
          static_cast<uint32_t>(colour_channels(file.header()).size())};
}

}  // namespace

bool is_exr(std::span<const std::byte> bytes) {
  return bytes.size() >= 4 && Imf::isImfMagic(reinterpret_cast<const char*>(bytes.data()));
}

ImageHeader exr_header(std::span<const std::byte> bytes) {
  limit_sizes();
  MemoryInput stream(bytes);
  Imf::InputFile file(stream, 1);
  return header_of(file);
}

DecodedImage exr_decode(std::span<const std::byte> bytes) {
  limit_sizes();
  MemoryInput stream(bytes);
  Imf::InputFile file(stream, 1);
  DecodedImage image{header_of(file), true, {}};
  const uint32_t w = image.header.width, c = image.header.channels;
  image.pixels.assign(size_t(w) * image.header.height * c, 0.0f);
  const Imath::Box2i window = file.header().dataWindow();
  // Slices address pixel (x, y) of the data window as base + x * xStride + y * yStride.
  char* origin = reinterpret_cast<char*>(image.pixels.data()) -
                 (ptrdiff_t(window.min.x) + ptrdiff_t(window.min.y) * w) * ptrdiff_t(c * sizeof(float));
  Imf::FrameBuffer frame;
  const std::vector<std::string> names = colour_channels(file.header());
  for (size_t i = 0; i < names.size(); ++i)
    frame.insert(names[i], Imf::Slice(Imf::FLOAT, origin + i * sizeof(float), c * sizeof(float), size_t(w) * c * sizeof(float)));
  file.setFrameBuffer(frame);
  file.readPixels(window.min.y, window.max.y);
  return image;
}

std::vector<unsigned char> exr_encode(const FloatImage& image) {
  Imf::Header header(static_cast<int>(image.width), static_cast<int>(image.height));
  header.compression() = Imf::ZIP_COMPRESSION;
  const size_t c = image.channel_names.size();
  Imf::FrameBuffer frame;
  char* base = const_cast<char*>(reinterpret_cast<const char*>(image.pixels.data()));  // read only when writing
  for (size_t i = 0; i < c; ++i) {
    header.channels().insert(image.channel_names[i], Imf::Channel(Imf::FLOAT));
    frame.insert(image.channel_names[i], Imf::Slice(Imf::FLOAT, base + i * sizeof(float), c * sizeof(float),
                                                    size_t(image.width) * c * sizeof(float)));
  }
  MemoryOutput stream;
  {
    Imf::OutputFile file(stream, header, 1);
    file.setFrameBuffer(frame);
    file.writePixels(static_cast<int>(image.height));
  }  // the destructor writes the line offsets
  return stream.take();
}

}  // namespace sdfbench::codec
