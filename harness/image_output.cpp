#include "harness/image_output.h"

#include <algorithm>


#include "renderers/shading/gpu_types.h"
#include "util/atomic_file.h"
#include "util/error.h"
#include "util/image_codec.h"

namespace sdfbench {
namespace {

namespace fs = std::filesystem;

// The format of `path` by its extension, or Error naming `what`.
ImageFormat format_of(const fs::path& path, const std::string& what) {
  const std::optional<ImageFormat> format = image_format_of(path);
  if (!format)
    throw Error(what + " '" + path.string() + "': unsupported image format '" + path.extension().string() + "' (use " +
                kImageExtensions + ")");
  return *format;
}

// Encoded in memory, then written with write_file_atomically: the image goes through the one
// safe way to write an output.
void write_atomically(const fs::path& path, const FloatImage& image) {
  // (appended, not "'" + path.string() + "'": GCC 12 gives a false -Wrestrict there, GCC bug 105651)
  const std::string quoted = std::string("'").append(path.string()).append("'");
  const std::vector<unsigned char> encoded = encode_image(image, format_of(path, "cannot write"), quoted);
  write_file_atomically(path, std::as_bytes(std::span(encoded.data(), encoded.size())));
}

bool is_exr(const fs::path& path) { return image_format_of(path) == ImageFormat::exr; }

float id_to_float(uint32_t id) {
  if (id == shading::NO_INSTANCE_VALUE) return -1.0f;
  if (id == shading::FLOOR_INSTANCE_VALUE) return -2.0f;
  return static_cast<float>(id);
}

// A viridis-like colour map (perceptually ordered, readable in grey and by colour-blind
// readers), piecewise linear through five of viridis' colours; x in [0, 1].
glm::vec3 colour_map(float x) {
  static const glm::vec3 stops[] = {{0.267f, 0.005f, 0.329f}, {0.231f, 0.322f, 0.545f}, {0.129f, 0.569f, 0.549f},
                                    {0.369f, 0.788f, 0.384f}, {0.993f, 0.906f, 0.144f}};
  const float s = glm::clamp(x, 0.0f, 1.0f) * 4.0f;
  const int i = std::min(static_cast<int>(s), 3);
  return glm::mix(stops[i], stops[i + 1], s - static_cast<float>(i));
}

}  // namespace

void check_image_path(const fs::path& path, const char* what) {
  check_output_path(path, what);
  format_of(path, what);
}

void check_aov_path(const fs::path& path, const char* what) {
  if (!path.empty() && !is_exr(path))
    throw Error(std::string(what) + " '" + path.string() + "': the AOVs are 7 float channels, which only OpenEXR holds (use .exr)");
  check_image_path(path, what);
}

FloatImage color_image(const FrameImages& images) {
  FloatImage image{images.width, images.height, {"R", "G", "B", "A"}, {}};
  image.pixels.reserve(images.color.size() * 4);
  for (const glm::vec4& c : images.color) image.pixels.insert(image.pixels.end(), {c.x, c.y, c.z, c.w});
  return image;
}

void write_color_image(const FrameImages& images, const fs::path& path) { write_atomically(path, color_image(images)); }

HeatmapRange write_heatmap(const std::vector<uint32_t>& values, uint32_t width, uint32_t height, const fs::path& path) {
  HeatmapRange range;
  if (!values.empty()) {
    std::vector<uint32_t> sorted = values;
    std::sort(sorted.begin(), sorted.end());
    range = {sorted[(sorted.size() - 1) * 99 / 100], sorted.back()};
  }
  FloatImage image{width, height, {"R", "G", "B"}, {}};
  image.pixels.reserve(values.size() * 3);
  for (uint32_t v : values) {
    const glm::vec3 c = colour_map(range.top > 0 ? static_cast<float>(v) / static_cast<float>(range.top) : 0.0f);
    image.pixels.insert(image.pixels.end(), {c.x, c.y, c.z});
  }
  write_atomically(path, image);
  return range;
}

FloatImage difference_map(const FrameImages& test, const FrameImages& reference) {
  if (test.width != reference.width || test.height != reference.height)
    throw Error("difference map: the frames' sizes differ");
  FloatImage image{test.width, test.height, {"R", "G", "B"}, {}};
  image.pixels.reserve(test.color.size() * 3);
  for (size_t i = 0; i < test.color.size(); ++i) {
    const glm::vec3 error = glm::abs(glm::vec3(test.color[i]) - glm::vec3(reference.color[i]));
    const glm::vec3 c = colour_map(std::max({error.x, error.y, error.z}) / kDifferenceMapTop);
    image.pixels.insert(image.pixels.end(), {c.x, c.y, c.z});
  }
  return image;
}

void write_difference_map(const FrameImages& test, const FrameImages& reference, const fs::path& path) {
  write_atomically(path, difference_map(test, reference));
}

void write_aov_image(const FrameImages& images, const fs::path& path) {
  check_aov_path(path, "--aov");
  constexpr int kChannels = 7;
  FloatImage image{images.width, images.height, {"hit", "depth", "instance_id", "primitive_id", "N.x", "N.y", "N.z"}, {}};
  const size_t pixels = images.depth.size();
  std::vector<float>& data = image.pixels;
  data.resize(pixels * kChannels);
  for (size_t i = 0; i < pixels; ++i) {
    float* px = &data[i * kChannels];
    const uint32_t id = images.instance_id[i];
    px[0] = id < shading::FLOOR_INSTANCE_VALUE ? 1.0f : 0.0f;  // an instance, not floor or sky
    px[1] = images.depth[i];
    px[2] = id_to_float(id);
    px[3] = id == shading::NO_INSTANCE_VALUE ? -1.0f : static_cast<float>(images.primitive_id[i]);
    px[4] = images.normal[i].x;
    px[5] = images.normal[i].y;
    px[6] = images.normal[i].z;
  }
  write_atomically(path, image);
}

}  // namespace sdfbench
